// Scene files: the shipped scenes parse cleanly; each kind of bad file gets its own clear
// diagnostic (wrong type with the JSON path, unknown key warning, missing file, malformed
// JSON, dangling reference); camera keyframes interpolate; scene names resolve.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "raster/scene_file/scene_build.h"
#include "raster/scene_file/scene_library.h"
#include "raster/scene_file/scene_parse.h"
#include "raster/geometry/snake.h"
#include "procedural/heightfield.h"
#include "procedural/normal_map.h"

namespace fs = std::filesystem;
using namespace tessera;

namespace {

const fs::path kScenes = fs::path(TESSERA_TEST_DATA) / ".." / ".." / "examples" / "scenes";

// A minimal valid scene with `extra` spliced in as further top-level members.
std::string scene_with(const std::string& objects, const std::string& extra = "") {
    return R"({"materials": {"m": {"model": "phong", "kd": [0.5, 0.5, 0.5]}}, "objects": )" + objects +
           (extra.empty() ? "" : ", " + extra) + "}";
}

const std::string kSphere = R"([{"type": "sphere", "material": "m", "radius": 1}])";

// The message of the SceneFileError that parsing `text` throws ("" if it does not throw).
std::string parse_error(const std::string& text) {
    std::vector<std::string> warnings;
    try {
        scene_file::parse_scene(text, "x.json", warnings);
    } catch (const scene_file::SceneFileError& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST(SceneFile, EveryShippedSceneParsesWithoutWarnings) {
    const std::vector<std::string> names = scene_file::available_scenes({kScenes});
    for (const char* expected : {"snakes", "flag", "toon", "bumpcube", "terrain", "metaballs", "stress"})
        EXPECT_NE(std::find(names.begin(), names.end(), expected), names.end()) << expected;
    for (const std::string& name : names) {
        std::vector<std::string> warnings;
        const scene_file::SceneSpec spec = scene_file::load_scene_file(scene_file::find_scene(name, {kScenes}), warnings);
        EXPECT_TRUE(warnings.empty()) << name << ": " << (warnings.empty() ? "" : warnings.front());
        EXPECT_FALSE(spec.objects.empty() && spec.passes.empty()) << name;
        EXPECT_FALSE(spec.lights.empty()) << name;
    }
}

// A normal map is a surface's texture, not its shape: on every shipped scene the relief's
// normals tilt the surface by a few degrees on average, never so far that the lit faces of
// the object underneath stop reading (the bumpcube's cube once vanished under its stone).
TEST(SceneFile, ShippedNormalMapsTextureTheSurfaceWithoutHidingIt) {
    int maps = 0;
    for (const std::string& name : scene_file::available_scenes({kScenes})) {
        std::vector<std::string> warnings;
        const scene_file::SceneSpec spec = scene_file::load_scene_file(scene_file::find_scene(name, {kScenes}), warnings);
        for (const scene_file::TextureSpec& t : spec.textures) {
            if (t.kind != scene_file::TextureSpec::Kind::relief_normals) continue;
            const procedural::NormalMap normals = procedural::normal_map(
                procedural::generate_heightfield(t.size, t.size, t.relief), t.strength, procedural::Boundary::periodic);
            double tilt = 0.0;
            const size_t texels = normals.xyz.size() / 3;
            for (size_t i = 0; i < texels; ++i)
                tilt += std::acos(std::clamp(double(normals.xyz[3 * i + 2]), -1.0, 1.0));
            const double mean_degrees = tilt / double(texels) * 180.0 / 3.14159265358979;
            EXPECT_GT(mean_degrees, 1.0) << name << ": " << t.name;
            EXPECT_LT(mean_degrees, 15.0) << name << ": " << t.name;
            ++maps;
        }
    }
    EXPECT_GE(maps, 2);
}

TEST(SceneFile, SnakesSceneHasItsIngredients) {
    std::vector<std::string> warnings;
    const scene_file::SceneSpec s = scene_file::load_scene_file(kScenes / "snakes.json", warnings);
    int snakes = 0, grounds = 0;
    for (const scene_file::ObjectSpec& o : s.objects) {
        snakes += o.shape == scene_file::ObjectSpec::Shape::snake;
        grounds += o.shape == scene_file::ObjectSpec::Shape::heightfield;
    }
    EXPECT_GE(snakes, 3);
    EXPECT_EQ(grounds, 1);
    bool rd = false;
    for (const scene_file::TextureSpec& t : s.textures) rd |= t.kind == scene_file::TextureSpec::Kind::reaction_diffusion;
    EXPECT_TRUE(rd);
    EXPECT_EQ(s.shadows, "rays");
}

TEST(SceneFile, WrongTypeNamesTheJsonPath) {
    EXPECT_EQ(parse_error(R"({"materials": {"m": {"kd": "red"}}, "objects": [{"type": "sphere", "material": "m"}]})"),
              "x.json: /materials/m/kd: expected an array of 3 numbers");
    EXPECT_EQ(parse_error(scene_with(R"([{"type": "sphere", "material": "m"}, {"type": "sphere", "material": "m"},
                                         {"type": "sphere", "material": "m", "radius": "big"}])")),
              "x.json: /objects/2/radius: expected a number, got a string");
    EXPECT_EQ(parse_error(scene_with(kSphere, R"("camera": {"eye": [0, 1]})")),
              "x.json: /camera/eye: expected an array of 3 numbers");
    EXPECT_EQ(parse_error(scene_with(kSphere, R"("lights": {"position": [0, 1, 0]})")),
              "x.json: /lights: expected an array, got an object");
    EXPECT_EQ(parse_error(scene_with(R"([{"type": "sphere", "material": "m", "tessellation": [8, 2.5]}])")),
              "x.json: /objects/0/tessellation/1: expected an integer");
}

TEST(SceneFile, OutOfRangeValuesAreErrorsWithThePath) {
    EXPECT_EQ(parse_error(scene_with(R"([{"type": "sphere", "material": "m", "radius": -1}])")),
              "x.json: /objects/0/radius: must be positive");
    EXPECT_EQ(parse_error(scene_with(kSphere, R"("camera": {"fov": 200})")),
              "x.json: /camera/fov: must lie in (0, 179) degrees");
    const std::string opacity = parse_error(
        R"({"materials": {"m": {"opacity": 2}}, "objects": [{"type": "sphere", "material": "m"}]})");
    EXPECT_NE(opacity.find("x.json: /materials/m: "), std::string::npos) << opacity;
    EXPECT_NE(opacity.find("opacity"), std::string::npos) << opacity;
    EXPECT_EQ(parse_error(scene_with(R"([{"type": "cone", "material": "m"}])")).rfind("x.json: /objects/0/type: unknown object type 'cone'", 0),
              0u);
}

TEST(SceneFile, DanglingReferencesAreErrors) {
    EXPECT_EQ(parse_error(scene_with(R"([{"type": "sphere", "material": "nope"}])")),
              "x.json: /objects/0/material: material 'nope' is not defined in /materials");
    EXPECT_EQ(parse_error(R"({"materials": {"m": {"diffuse_texture": "skin"}}, "objects": []})"),
              "x.json: /materials/m: texture 'skin' is not defined in /textures");
    EXPECT_EQ(parse_error(scene_with(R"([{"type": "snake", "material": "m", "ground": "sand"}])")),
              "x.json: /objects/0/ground: no heightfield object is named 'sand'");
    EXPECT_EQ(parse_error(R"({"objects": []})" ).empty(), true);
    EXPECT_EQ(parse_error(R"({"materials": {}})"), "x.json: /: missing required key 'objects'");
}

TEST(SceneFile, UnknownKeysAreWarningsNamingFileAndPath) {
    std::vector<std::string> warnings;
    scene_file::parse_scene(scene_with(R"([{"type": "sphere", "material": "m", "radius": 1, "colour": [1, 0, 0]}])",
                           R"("camrea": {}, "lights": [{"direction": [0, 1, 0], "Lx": [1, 1, 1]}], "a/b": 1)"),
                "x.json", warnings);
    ASSERT_EQ(warnings.size(), 4u);
    const auto has = [&](const std::string& text) {
        return std::find(warnings.begin(), warnings.end(), text) != warnings.end();
    };
    EXPECT_TRUE(has("x.json: /objects/0/colour: unknown key 'colour'; ignored"));
    EXPECT_TRUE(has("x.json: /camrea: unknown key 'camrea'; ignored"));
    EXPECT_TRUE(has("x.json: /lights/0/Lx: unknown key 'Lx'; ignored"));
    EXPECT_TRUE(has("x.json: /a~1b: unknown key 'a/b'; ignored"));  // RFC 6901 escaping
}

TEST(SceneFile, ParametersTheModelDoesNotUseAreWarnings) {
    std::vector<std::string> warnings;
    scene_file::parse_scene(R"({"materials": {"cel": {"model": "toon", "ks": [1, 1, 1]}},
                    "objects": [{"type": "sphere", "material": "cel"}]})",
                "x.json", warnings);
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_EQ(warnings[0], "x.json: /materials/cel: material parameter 'ks' is not used by the toon model; ignored");
}

// A diffuse texture is an albedo map: it colours the ambient term too unless the material says
// otherwise, so faces only the ambient light reaches keep their texture.
TEST(SceneFile, DiffuseTexturesColourTheAmbientTermByDefault) {
    std::vector<std::string> warnings;
    const scene_file::SceneSpec s = scene_file::parse_scene(R"({
        "textures": {"skin": {"type": "reaction_diffusion", "size": 16, "steps": 1}},
        "materials": {"albedo": {"diffuse_texture": "skin"},
                      "flat": {"diffuse_texture": "skin", "ambient_texture": false},
                      "plain": {"ambient_texture": true}},
        "objects": [{"type": "sphere", "material": "albedo"}]})",
        "x.json", warnings);
    ASSERT_EQ(s.materials.size(), 3u);
    EXPECT_TRUE(s.materials[0].material.textured_ambient);
    EXPECT_FALSE(s.materials[1].material.textured_ambient);
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_EQ(warnings[0], "x.json: /materials/plain: 'ambient_texture' without a 'diffuse_texture' has no effect");
}

TEST(SceneFile, MissingFileAndMalformedJson) {
    std::vector<std::string> warnings;
    try {
        scene_file::load_scene_file("/nonexistent/scene.json", warnings);
        FAIL() << "no error";
    } catch (const scene_file::SceneFileError& e) {
        EXPECT_EQ(std::string(e.what()), "cannot read scene file '/nonexistent/scene.json': no such file");
    }
    const std::string err = parse_error("{\"objects\": [\n  {\"type\": \"sphere\",, }\n]}");
    EXPECT_EQ(err.rfind("x.json: malformed JSON: parse error at line 2, column ", 0), 0u) << err;
    EXPECT_EQ(parse_error("[1, 2]"), "x.json: /: expected an object, got an array");
}

TEST(SceneFile, UnknownSceneNameListsTheAvailableOnes) {
    try {
        scene_file::find_scene("snaeks", {kScenes});
        FAIL() << "no error";
    } catch (const std::invalid_argument& e) {
        const std::string m = e.what();
        EXPECT_NE(m.find("unknown scene 'snaeks'"), std::string::npos) << m;
        EXPECT_NE(m.find("snakes"), std::string::npos) << m;
        EXPECT_NE(m.find("metaballs"), std::string::npos) << m;
    }
    EXPECT_EQ(scene_file::find_scene("my/scene.json", {kScenes}), fs::path("my/scene.json"));
    EXPECT_EQ(fs::weakly_canonical(scene_file::find_scene("flag", {kScenes})), fs::weakly_canonical(kScenes / "flag.json"));
}

TEST(SceneFile, CameraKeyframesInterpolateThroughEveryKey) {
    render::CameraSpec spec;
    spec.keys = {{0.0f, {0, 1, 5}, {0, 0, 0}, 40}, {1.0f, {2, 1, 3}, {1, 0, 0}, 50}, {3.0f, {4, 2, 0}, {2, 0, -1}, 60}};
    for (const render::CameraKey& k : spec.keys) {
        const Camera c = render::camera_at(spec, k.time, 1.5f);
        EXPECT_NEAR(glm::distance(c.eye, k.eye), 0.0f, 1e-5f);
        EXPECT_NEAR(glm::distance(c.lookat, k.lookat), 0.0f, 1e-5f);
        EXPECT_NEAR(c.fovy_deg, k.fovy_deg, 1e-4f);
        EXPECT_EQ(c.aspect, 1.5f);
    }
    EXPECT_EQ(render::camera_at(spec, -1.0f, 1.0f).eye, spec.keys.front().eye);  // holds before the first key
    EXPECT_EQ(render::camera_at(spec, 9.0f, 1.0f).eye, spec.keys.back().eye);    // and after the last
    // Continuous: small steps in time give small steps in position.
    glm::vec3 last = render::camera_at(spec, 0.0f, 1.0f).eye;
    for (float t = 0.01f; t <= 3.0f; t += 0.01f) {
        const glm::vec3 e = render::camera_at(spec, t, 1.0f).eye;
        EXPECT_LT(glm::distance(e, last), 0.1f) << t;
        last = e;
    }
}

TEST(SceneFile, SnakeRestsOnTheGroundAndKeepsItsLength) {
    scene_file::SnakeSpec s;
    const geometry::GroundHeight ground = [](float x, float z) { return 0.3f * std::sin(x) + 0.1f * z; };
    for (float t : {0.0f, 0.7f, 5.3f}) {
        const std::vector<glm::vec3> spine = geometry::snake_spine(s, t, ground);
        ASSERT_EQ(int(spine.size()), s.control_points);
        float arc = 0.0f;
        for (size_t i = 0; i < spine.size(); ++i) {
            // Above the sand, by less than the body's height (+ the raised head).
            const float above = spine[i].y - ground(spine[i].x, spine[i].z);
            EXPECT_GE(above, 0.0f);
            EXPECT_LE(above, s.width * (s.height_ratio + 0.5f));
            if (i > 0) arc += glm::distance(glm::vec2(spine[i].x, spine[i].z), glm::vec2(spine[i - 1].x, spine[i - 1].z));
        }
        // The path spacing keeps the body near its length (the sway adds a little).
        EXPECT_GT(arc, 0.8f * s.length);
        EXPECT_LT(arc, 1.5f * s.length);
        const Mesh body = geometry::snake_body(s, spine);
        EXPECT_EQ(body.vertex_count(), size_t(s.tessellation.x + 1) * size_t(s.tessellation.y + 1));
        for (const glm::vec3& n : body.normals) ASSERT_TRUE(std::isfinite(n.x) && std::isfinite(n.y) && std::isfinite(n.z));
    }
    // It moves: the head is elsewhere a second later.
    EXPECT_GT(glm::distance(geometry::snake_spine(s, 0.0f, ground).back(), geometry::snake_spine(s, 1.0f, ground).back()), 0.05f);
}

// The body is an open tube: its front ring must lie inside the head at every moment, on flat
// and on sloping ground, or the floor shows through a crack at the neck.
TEST(SceneFile, SnakeNeckRingLiesInsideTheHead) {
    scene_file::SnakeSpec s;
    const geometry::GroundHeight ground = [](float x, float z) { return 0.3f * std::sin(x) + 0.1f * z; };
    for (float t : {0.0f, 0.7f, 1.9f, 3.3f, 5.0f, 8.2f}) {
        const std::vector<glm::vec3> spine = geometry::snake_spine(s, t, ground);
        const Mesh body = geometry::snake_body(s, spine);
        const geometry::SnakeHead head = geometry::snake_head(s, spine);
        const size_t ring = size_t(s.tessellation.y) + 1;
        float outermost = 0.0f;  // 1: on the head's surface
        for (size_t i = body.vertex_count() - ring; i < body.vertex_count(); ++i) {
            const glm::vec3 local = glm::inverse(head.orientation) * (body.positions[i] - head.centre);
            outermost = std::max(outermost, glm::length(local / head.radii));
        }
        EXPECT_LT(outermost, 0.97f) << "the neck ring leaves the head at time " << t;
    }
}

TEST(SceneFile, MeshObjectsLoadObjFilesRelativeToTheScene) {
    const fs::path dir = fs::temp_directory_path() / ("tessera_scene_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    std::ofstream(dir / "tri.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    std::ofstream(dir / "scene.json") << scene_with(R"([{"type": "mesh", "material": "m", "file": "tri.obj"}])");
    std::ofstream(dir / "broken.json") << scene_with(R"([{"type": "mesh", "material": "m", "file": "nope.obj"}])");
    std::vector<std::string> warnings;
    const render::AnimatedScene scene = scene_file::build_scene(scene_file::load_scene_file(dir / "scene.json", warnings));
    ASSERT_EQ(scene.scene.objects.size(), 1u);
    EXPECT_EQ(scene.scene.objects[0].geometry->triangle_count(), 1u);
    try {
        scene_file::build_scene(scene_file::load_scene_file(dir / "broken.json", warnings));
        ADD_FAILURE() << "no error";
    } catch (const scene_file::SceneFileError& e) {
        const std::string m = e.what();
        EXPECT_NE(m.find("broken.json: /objects/0/file: cannot read"), std::string::npos) << m;
        EXPECT_NE(m.find("nope.obj"), std::string::npos) << m;
    }
    fs::remove_all(dir);
}
