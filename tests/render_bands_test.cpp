// Frames rendered in bands (issue 8: frames beyond 8K stream into the file): a region's
// camera sees each pixel through the same ray as the whole frame's, so a banded render agrees
// with the whole-frame render — everything but pixels on an exact triangle edge, where the
// region's rounding may pick the neighbour — for every stage: raster and ray-cast
// visibility, shadow maps and rays, transparency, sky, marched metaballs and fog. And the
// streamed file holds exactly the bands written, or nothing.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <tuple>

#include "raster/core/camera.h"
#include "raster/core/error.h"
#include "raster/io/image_stream.h"
#include "raster/output/frame_encoding.h"
#include "raster/render/frame_renderer.h"
#include "raster/scene_file/scene_build.h"
#include "raster/scene_file/scene_parse.h"

namespace fs = std::filesystem;
using namespace tessera;

namespace {

// A floor, an opaque ball casting a shadow, a glass ball, metaballs and fog under a sky.
const char* kEveryStage = R"({
  "camera": {"eye": [0.3, 2.5, 4.5], "lookat": [0, 0, 0], "fov": 55},
  "background": {"type": "sky", "sun_direction": [0.3, 0.8, 0.4]},
  "lights": [{"direction": [0.3, 0.8, 0.4], "La": [0.2, 0.2, 0.2], "Le": [1, 1, 1]}],
  "materials": {"grey": {"model": "phong", "kd": [0.6, 0.6, 0.6], "ka": [0.5, 0.5, 0.5], "ks": [0.2, 0.2, 0.2]},
                "red": {"model": "phong", "kd": [0.8, 0.1, 0.1], "ks": [0.6, 0.6, 0.6], "shine": 40},
                "glass": {"model": "phong", "kd": [0.2, 0.4, 0.9], "opacity": 0.4}},
  "objects": [
    {"type": "box", "material": "grey", "size": [6, 0.2, 6], "transform": {"translate": [0, -1.1, 0]}},
    {"type": "sphere", "material": "red", "radius": 0.5, "tessellation": [32, 16], "centre": [-0.8, 0, 0]},
    {"type": "sphere", "material": "glass", "radius": 0.6, "tessellation": [32, 16], "centre": [0.9, -0.2, 0.8]}
  ],
  "passes": [
    {"type": "metaballs", "count": 3, "radius": 0.5, "orbit_scale": 0.6, "offset": [0.6, 0.9, -1.2],
     "material": {"kd": [0.2, 0.8, 0.3]}},
    {"type": "fog", "density": [0.04, 0.04, 0.05], "colour": [0.7, 0.75, 0.8], "falloff": 1.0, "base_height": 0}
  ]
})";

render::AnimatedScene every_stage() {
    std::vector<std::string> warnings;
    render::AnimatedScene s = scene_file::build_scene(scene_file::parse_scene(kEveryStage, "bands.json", warnings));
    EXPECT_TRUE(warnings.empty()) << warnings.front();
    return s;
}

// The banded frame assembled in memory, checking that bands arrive in order with the
// layout's rows.
Frame render_in_bands(render::FrameRenderer& renderer, const render::BandLayout& layout, float time) {
    Frame whole(layout.width, layout.height);
    int expected = 0;
    renderer.render_bands(time, layout, [](int) { return true; }, [&](int b, const Frame& band) {
        EXPECT_EQ(b, expected++);
        const auto [y0, y1] = layout.rows(b);
        EXPECT_EQ(band.width, layout.width);
        EXPECT_EQ(band.height, y1 - y0);
        std::copy(band.pixels.begin(), band.pixels.end(), whole.pixels.begin() + ptrdiff_t(y0) * layout.width);
    });
    EXPECT_EQ(expected, layout.bands());
    return whole;
}

}  // namespace

TEST(CameraRegion, SeesEveryPointAtThePixelTheWholeFrameDoes) {
    Camera c;
    c.eye = {1, 2, 5};
    c.lookat = {0, 0.5f, 0};
    c.aspect = 1000.0f / 700.0f;
    const Camera region = c.region(1000, 700, 300, 200, 250, 100);
    const Camera nested = region.region(250, 100, 50, 20, 100, 60);  // a region of the region
    const auto window = [](const Camera& cam, glm::vec3 p, int w, int h) {
        const glm::vec4 clip = cam.view_projection() * glm::vec4(p, 1.0f);
        return glm::dvec2((clip.x / clip.w + 1.0) * 0.5 * w, (1.0 - clip.y / clip.w) * 0.5 * h);
    };
    for (const glm::vec3 p : {glm::vec3(0, 0, 0), glm::vec3(-1.3f, 0.2f, 1), glm::vec3(2, 1.5f, -3)}) {
        const glm::dvec2 whole = window(c, p, 1000, 700);
        const glm::dvec2 in_region = window(region, p, 250, 100) + glm::dvec2(300, 200);
        const glm::dvec2 in_nested = window(nested, p, 100, 60) + glm::dvec2(350, 220);
        EXPECT_NEAR(in_region.x, whole.x, 1e-3);
        EXPECT_NEAR(in_region.y, whole.y, 1e-3);
        EXPECT_NEAR(in_nested.x, whole.x, 1e-3);
        EXPECT_NEAR(in_nested.y, whole.y, 1e-3);
    }
    // The whole frame as a region is the camera itself.
    EXPECT_TRUE(c.region(1000, 700, 0, 0, 1000, 700).window.whole());
}

class RenderBands : public ::testing::TestWithParam<std::tuple<render::RendererKind, render::ShadowMode>> {};

TEST_P(RenderBands, AgreeWithTheWholeFrameExceptOnTriangleEdges) {
    const auto [renderer_kind, shadows] = GetParam();
    constexpr int kWidth = 320, kHeight = 200;
    render::AnimatedScene scene = every_stage();
    render::FrameRenderer renderer(scene, kWidth, kHeight, renderer_kind, shadows);
    const Frame whole = renderer.render(0.7f);
    // Bands of 48 rows cut into regions 100 wide: seams in both directions, a short last band
    // and a narrow last region.
    const render::BandLayout layout{kWidth, kHeight, 48, 100};
    const Frame banded = render_in_bands(renderer, layout, 0.7f);

    int differing = 0;
    double worst = 0.0;
    for (size_t i = 0; i < whole.pixels.size(); ++i) {
        const glm::vec4 d = glm::abs(whole.pixels[i] - banded.pixels[i]);
        const double m = std::max({d.r, d.g, d.b, d.a});
        worst = std::max(worst, m);
        differing += m > 2e-3;
    }
    // Edge pixels and the last bits of the marched and fogged pixels may differ; a seam or a
    // shifted region would differ in thousands.
    EXPECT_LE(differing, int(whole.pixels.size() / 200)) << "worst difference " << worst;
}

INSTANTIATE_TEST_SUITE_P(RenderFrame, RenderBands,
                         ::testing::Combine(::testing::Values(render::RendererKind::raster, render::RendererKind::raytrace),
                                            ::testing::Values(render::ShadowMode::none, render::ShadowMode::map, render::ShadowMode::rays)));

TEST(RenderBands, OnlyTheChosenBandsAreRenderedAndTheyAreTheSame) {
    render::AnimatedScene scene = every_stage();
    render::FrameRenderer renderer(scene, 160, 100, render::RendererKind::raster, render::ShadowMode::map);
    const render::BandLayout layout{160, 100, 32, 64};
    const Frame all = render_in_bands(renderer, layout, 0.2f);
    std::vector<int> seen;
    renderer.render_bands(0.2f, layout, [](int b) { return b % 2 == 1; }, [&](int b, const Frame& band) {
        seen.push_back(b);
        const int y0 = layout.rows(b).first;
        for (int y = 0; y < band.height; ++y)
            for (int x = 0; x < band.width; ++x) ASSERT_EQ(band.at(x, y), all.at(x, y0 + y)) << x << "," << y;
    });
    EXPECT_EQ(seen, (std::vector<int>{1, 3}));
}

TEST(RenderBands, LayoutFollowsTheFrameSizeAlone) {
    EXPECT_FALSE(render::needs_bands(7680, 4320));
    EXPECT_FALSE(render::needs_bands(8192, 8192));
    EXPECT_TRUE(render::needs_bands(8193, 100));
    EXPECT_TRUE(render::needs_bands(100, 16384));
    const render::BandLayout l = render::band_layout(16384, 16384);
    EXPECT_EQ(l.band_rows % 128, 0);
    EXPECT_LE(l.region_width, pipeline::kMaxViewport);
    EXPECT_LE(int64_t(l.band_rows) * l.width, int64_t(1) << 23);
    EXPECT_EQ(l.rows(l.bands() - 1).second, 16384);
    EXPECT_EQ(render::band_layout(300, 100).bands(), 1);
    render::AnimatedScene scene = every_stage();
    render::FrameRenderer renderer(scene, 100, 60, render::RendererKind::raster, render::ShadowMode::none);
    EXPECT_THROW(renderer.render_bands(0.0f, render::BandLayout{120, 60, 16, 64}, [](int) { return true; },
                                       [](int, const Frame&) {}),
                 std::invalid_argument);
}

namespace {

fs::path scratch(const std::string& name) {
    const fs::path dir = fs::temp_directory_path() / ("tessera_stream_" + std::to_string(getpid()));
    fs::create_directories(dir);
    return dir / name;
}

Frame gradient(int w, int h) {
    Frame f(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) f.at(x, y) = {float(x) / float(w), float(y) / float(h), 0.25f + 0.001f * float(x % 7), 1.0f};
    return f;
}

void stream(const fs::path& path, const Frame& frame, int band_rows) {
    io::ImageStream file(path, frame.width, frame.height, 4, output::frame_pixel_type(path));
    for (int y0 = 0; y0 < frame.height; y0 += band_rows) {
        const int rows = std::min(band_rows, frame.height - y0);
        Frame band(frame.width, rows);
        std::copy_n(frame.pixels.begin() + ptrdiff_t(y0) * frame.width, size_t(rows) * frame.width, band.pixels.begin());
        file.write_rows(y0, output::encode_frame(path, band).view());
    }
    file.commit();
}

}  // namespace

TEST(ImageStream, BandsMakeTheSameImageAsAWholeWrite) {
    const Frame frame = gradient(200, 150);  // 150 = 2 bands of 64 and a short one
    for (const char* name : {"s.exr", "s.tif", "s.png"}) {
        const fs::path streamed = scratch(name), whole = scratch(std::string("whole_") + name);
        stream(streamed, frame, 64);
        output::write_frame(whole, frame);
        const io::FloatImage a = io::read_image(streamed), b = io::read_image(whole);
        ASSERT_EQ(a.width, 200);
        ASSERT_EQ(a.height, 150);
        EXPECT_EQ(a.pixels, b.pixels) << name;
    }
    fs::remove_all(scratch("").parent_path());
}

TEST(ImageStream, OutOfOrderOrMissingRowsAreErrorsAndLeaveNothing) {
    const fs::path path = scratch("broken.exr");
    const Frame band = gradient(64, 64);
    {
        io::ImageStream file(path, 64, 200, 4, io::PixelType::f32);
        EXPECT_THROW(file.write_rows(64, output::encode_frame(path, band).view()), Error);  // row 0 first
    }
    {
        io::ImageStream file(path, 64, 200, 4, io::PixelType::f32);
        file.write_rows(0, output::encode_frame(path, band).view());
        EXPECT_THROW(file.commit(), Error);  // 136 rows never came
    }
    {
        io::ImageStream file(path, 64, 200, 4, io::PixelType::f32);
        file.write_rows(0, output::encode_frame(path, band).view());
    }  // abandoned: no commit
    EXPECT_FALSE(fs::exists(path));
    EXPECT_TRUE(fs::is_empty(path.parent_path())) << "a temporary was left behind";
    fs::remove_all(path.parent_path());
}

TEST(ImageStream, FullDeviceIsAnError) {
    if (!fs::exists("/dev/full")) GTEST_SKIP() << "no /dev/full";
    const Frame frame = gradient(256, 128);
    // PNG writes in order, so the device takes it until the disk "fills"; tiled formats seek
    // back, which a device cannot: both are clear errors.
    for (const char* ext : {".png", ".exr"}) {
        EXPECT_THROW(
            {
                io::ImageStream file(fs::path("/dev/full"), 256, 128, 4, output::frame_pixel_type(std::string("x") + ext));
                file.write_rows(0, output::encode_frame(std::string("x") + ext, frame).view());
                file.commit();
            },
            Error)
            << ext;
    }
}
