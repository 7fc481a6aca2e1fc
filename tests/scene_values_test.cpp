// Scene values at their extremes (issue 19), in process: every value whose square or product
// would overflow, every content error the generators find while the scene is built, and every
// animated camera value is refused as "FILE: /json/pointer: ...", naming the value; extreme
// directions are accepted. (tests/cli_scene_values.sh renders the accepted ones and checks the
// command's contract: exit 1, no usage hint, no file left.)
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "raster/core/error.h"
#include "raster/output/frame_encoding.h"
#include "raster/render/animated_scene.h"
#include "raster/scene_file/scene_build.h"
#include "raster/scene_file/scene_file_error.h"
#include "raster/scene_file/scene_parse.h"

using namespace tessera;

namespace {

const std::string kEye = R"("eye": [0.5, 1.2, 4], "lookat": [0, 0, 0])";
const std::string kLight = R"({"direction": [1, 1, 1], "La": [0.1, 0.1, 0.1], "Le": [1, 1, 1]})";
const std::string kBox = R"({"type": "box", "material": "m", "transform": {"axis": [1, 1, 1], "angle": 30}})";

// A scene file from its parts (JSON fragments), as the shipped scenes are written.
std::string scene_text(const std::string& camera, const std::string& lights, const std::string& objects,
                  const std::string& extra = "", const std::string& kd = "[0.8, 0.5, 0.3]",
                  const std::string& texture = R"({"type": "relief_normals", "size": 32})") {
    return R"({"materials": {"m": {"kd": )" + kd + R"(, "ks": [0.5, 0.5, 0.5], "shine": 20},
                             "n": {"kd": [0.8, 0.8, 0.8], "normal_texture": "bumps"}},
               "textures": {"bumps": )" + texture + R"(},
               "camera": {)" + camera + R"(}, "lights": [)" + lights + R"(], "objects": [)" + objects + "]" + extra + "}";
}

// The SceneFileError of reading and then building `text` as x.json ("" when both succeed).
std::string scene_error(const std::string& text) {
    std::vector<std::string> warnings;
    try {
        scene_file::SceneSpec spec = scene_file::parse_scene(text, "x.json", warnings);
        spec.file = "x.json";
        (void)scene_file::build_scene(spec);
    } catch (const scene_file::SceneFileError& e) {
        return e.what();
    }
    return "";
}

struct Case {
    const char* what;
    std::string text;
    const char* pointer;  // the error starts "x.json: POINTER" (deeper pointers allowed)
};

}  // namespace

TEST(SceneValues, ValuesWhoseProductsOverflowAndContentErrorsNameTheValue) {
    const std::string sky = R"(, "background": {"type": "sky", "sun_direction": [0, 1, 0], "sun": [3e38, 1, 1]})";
    const std::string keys = kEye + R"(, "keyframes": [)";
    const std::vector<Case> cases = {
        {"Le of 3e38", scene_text(kEye, R"({"direction": [0, 1, 1], "Le": [3e38, 3e38, 3e38]})", kBox), "/lights/0/Le"},
        {"La of 3e38", scene_text(kEye, R"({"direction": [0, 1, 1], "La": [3e38, 3e38, 3e38]})", kBox), "/lights/0/La"},
        {"negative Le", scene_text(kEye, R"({"direction": [0, 1, 1], "Le": [-1, 0, 0]})", kBox), "/lights/0/Le"},
        {"point light at 3e38", scene_text(kEye, R"({"position": [3e38, 1, 1]})", kBox), "/lights/0/position"},
        {"kd of 3e38", scene_text(kEye, kLight, kBox, "", "[3e38, 3e38, 3e38]"), "/materials/m/kd"},
        {"background of 3e38", scene_text(kEye, kLight, kBox, R"(, "background": {"colour": [3e38, 0, 0]})"),
         "/background/colour"},
        {"sun of 3e38", scene_text(kEye, kLight, kBox, sky), "/background/sun"},
        {"eye at 3e38", scene_text(R"("eye": [3e38, 0, 0], "lookat": [-3e38, 0, 0])", kLight, kBox), "/camera/eye"},
        {"zero light direction", scene_text(kEye, R"({"direction": [0, 0, 0]})", kBox), "/lights/0/direction"},
        {"zero up", scene_text(kEye + R"(, "up": [0, 0, 0])", kLight, kBox), "/camera/up"},
        {"flag size [0, -2]", scene_text(kEye, kLight, R"({"type": "flag", "material": "m", "size": [0, -2]})"),
         "/objects/0/size"},
        {"torus minor > major",
         scene_text(kEye, kLight, kBox + R"(, {"type": "torus", "material": "m", "major": 0.2, "minor": 0.5})"), "/objects/1"},
        {"RD anisotropy 5",
         scene_text(kEye, kLight, kBox, "", "[0.8, 0.5, 0.3]",
               R"({"type": "reaction_diffusion", "size": 16, "steps": 10, "anisotropy": 5})"),
         "/textures/bumps/anisotropy"},
        {"heightfield gain 2",
         scene_text(kEye, kLight, R"({"type": "heightfield", "material": "m", "samples": [8, 8], "gain": 2})"),
         "/objects/0/gain"},
        {"eye on lookat", scene_text(R"("eye": [1, 2, 3], "lookat": [1, 2, 3])", kLight, kBox), "/camera"},
        {"up along the view", scene_text(R"("eye": [0, 5, 0], "lookat": [0, 0, 0])", kLight, kBox), "/camera"},
        {"terrain frequency 3e38", scene_text(kEye, kLight, kBox, R"(, "passes": [{"type": "terrain", "frequency": 3e38}])"),
         "/passes/0"},
        {"keyframe fov 190", scene_text(keys + R"({"time": 0}, {"time": 1, "fov": 190}])", kLight, kBox),
         "/camera/keyframes/1/fov"},
        {"keyframe fov 0", scene_text(keys + R"({"time": 0, "fov": 0}, {"time": 1}])", kLight, kBox),
         "/camera/keyframes/0/fov"},
        // 10, 170, 170, 10: Catmull-Rom overshoots past 180 between the two 170s.
        {"fov spline overshoot",
         scene_text(keys + R"({"time": 0, "fov": 10}, {"time": 0.5, "fov": 170}, {"time": 1, "fov": 170},
                         {"time": 1.5, "fov": 10}])", kLight, kBox),
         "/camera/keyframes"},
        {"fov spline undershoot",
         scene_text(keys + R"({"time": 0, "fov": 170}, {"time": 0.5, "fov": 4}, {"time": 1, "fov": 4},
                         {"time": 1.5, "fov": 170}])", kLight, kBox),
         "/camera/keyframes"},
        {"keyframe eye on lookat", scene_text(keys + R"({"time": 0}, {"time": 2, "eye": [0, 0, 0]}])", kLight, kBox),
         "/camera/keyframes/1"},
        {"keyframe up along the view", scene_text(keys + R"({"time": 0}, {"time": 2, "eye": [0, 3, 0]}])", kLight, kBox),
         "/camera/keyframes/1"},
    };
    for (const Case& c : cases) {
        const std::string error = scene_error(c.text);
        EXPECT_EQ(error.rfind(std::string("x.json: ") + c.pointer, 0), 0u) << c.what << ": " << error;
    }
}

TEST(SceneValues, DirectionsOfAnyLengthAndSaneSplinesAreAccepted) {
    for (const char* v : {"3e38, 3e38, 3e38", "1e-30, 1e-30, 1e-30", "1e-44, 1e-44, 1e-44", "-3e38, -3e38, -3e38"}) {
        const std::string axis = std::string(R"({"type": "box", "material": "m", "transform": {"axis": [)") + v +
                                 R"(], "angle": 30}, "spin": {"axis": [)" + v + R"(], "speed": 40}})";
        const std::string light = std::string(R"({"direction": [)") + v + R"(], "Le": [1, 1, 1]})";
        EXPECT_EQ(scene_error(scene_text(kEye, light, axis)), "") << v;
    }
    EXPECT_EQ(scene_error(scene_text(kEye + R"(, "up": [0, 3e38, 0])", kLight, kBox)), "");
    EXPECT_EQ(scene_error(scene_text(kEye + R"(, "keyframes": [{"time": 0, "fov": 40}, {"time": 0.5, "fov": 70},
                                  {"time": 1, "fov": 70}, {"time": 1.5, "fov": 40}])",
                                kLight, kBox)),
              "");
}

TEST(SceneValues, FovRangeFindsTheSplinesOvershoot) {
    std::vector<render::CameraKey> keys(4);
    const float fov[] = {10, 170, 170, 10};
    for (int i = 0; i < 4; ++i) keys[size_t(i)].time = 0.5f * float(i), keys[size_t(i)].fovy_deg = fov[i];
    const auto [low, high] = render::fov_range(keys, 1);
    EXPECT_NEAR(high, 190.0f, 0.5f);  // at the segment's middle: 170 + (170 - 10) / 8
    EXPECT_EQ(low, 170.0f);
    // A gentle change overshoots a little, within range: 40, 70, 70, 40 reach 73.75.
    const float gentle[] = {40, 70, 70, 40};
    for (int i = 0; i < 4; ++i) keys[size_t(i)].fovy_deg = gentle[i];
    const auto [gentle_low, gentle_high] = render::fov_range(keys, 1);
    EXPECT_EQ(gentle_low, 70.0f);
    EXPECT_NEAR(gentle_high, 73.75f, 1e-3f);
}

TEST(SceneValues, AFrameHoldingNanOrInfIsNeverEncoded) {
    Frame frame(4, 2, glm::vec4(0.5f));
    EXPECT_NO_THROW(output::encode_frame("f.exr", frame));
    frame.pixels[3].g = INFINITY;
    frame.pixels[5].a = NAN;
    for (const char* name : {"f.exr", "f.png", "f.tif"}) {
        try {
            output::encode_frame(name, frame);
            ADD_FAILURE() << name << ": a frame with NaN and Inf was encoded";
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find("2 pixel(s)"), std::string::npos) << e.what();
        }
    }
}
