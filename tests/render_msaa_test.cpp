// MSAA through the frame renderer: silhouettes and shadow edges get mixed colours, pixels
// inside a surface keep their single-sample colour exactly, raster and ray-cast frames agree,
// and the result is the same for any thread count.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <memory>

#include "raster/render/frame_renderer.h"
#include "raster/scene_file/scene_build.h"
#include "raster/scene_file/scene_parse.h"

using namespace tessera;

namespace {

// A red ball over a grey floor against a blue background, lit from above, with fog: every
// kind of pass runs on the layers (shading, shadows, a compute pass).
const char* kBall = R"({
  "camera": {"eye": [0, 2, 4], "lookat": [0, 0, 0], "fov": 45},
  "background": {"type": "colour", "colour": [0.2, 0.3, 0.9]},
  "lights": [{"direction": [0.3, 1, 0.2], "La": [0.2, 0.2, 0.2], "Le": [1, 1, 1]}],
  "materials": {"grey": {"model": "phong", "kd": [0.6, 0.6, 0.6], "ka": [0.5, 0.5, 0.5], "ks": [0, 0, 0]},
                "red": {"model": "phong", "kd": [0.9, 0.1, 0.1]}},
  "objects": [
    {"type": "box", "material": "grey", "size": [3, 0.2, 3], "transform": {"translate": [0, -1.1, 0]}},
    {"type": "sphere", "material": "red", "radius": 0.7, "tessellation": [24, 12], "centre": [0, 0, 0]}
  ],
  "passes": [{"type": "fog", "density": [0.02, 0.02, 0.02], "colour": [0.8, 0.8, 0.8], "falloff": 0.5, "base_height": 0}]
})";

// Metaballs marched against the sky, nothing rasterized: their silhouettes are the pass's own.
const char* kBalls = R"({
  "camera": {"eye": [0, 0.6, 4.2], "lookat": [0, 0, 0], "fov": 45},
  "background": {"type": "colour", "colour": [0.2, 0.3, 0.9]},
  "lights": [{"direction": [0.4, 0.55, 0.73], "La": [0.15, 0.15, 0.2], "Le": [1.2, 1.1, 1.0]}],
  "passes": [{"type": "metaballs", "count": 5, "radius": 0.9, "kernel": "wyvill", "threshold": 0.35,
              "material": {"kd": [0.85, 0.25, 0.12], "ka": [0.1, 0.05, 0.05]}}],
  "objects": []
})";

Frame render(int samples, render::RendererKind kind, render::ShadowMode shadows, int threads = 0,
             const char* json = kBall) {
    std::unique_ptr<tbb::global_control> limit;
    if (threads > 0) limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, threads);
    std::vector<std::string> warnings;
    render::AnimatedScene scene = scene_file::build_scene(scene_file::parse_scene(json, "scene.json", warnings));
    render::FrameRenderer renderer(scene, 120, 80, kind, shadows, samples);
    return renderer.render(0.0f);
}

float max_difference(const glm::vec4& a, const glm::vec4& b) {
    const glm::vec4 d = glm::abs(a - b);
    return std::max(std::max(d.r, d.g), std::max(d.b, d.a));
}

TEST(RenderMsaa, SilhouettesMixAndInsidesStay) {
    const Frame one = render(1, render::RendererKind::raster, render::ShadowMode::rays);
    const Frame four = render(4, render::RendererKind::raster, render::ShadowMode::rays);
    ASSERT_EQ(one.pixels.size(), four.pixels.size());
    size_t same = 0, mixed = 0;
    for (size_t p = 0; p < one.pixels.size(); ++p) {
        const float d = max_difference(one.pixels[p], four.pixels[p]);
        // Fog reads the depth, which for a surface is its nearest sample's, not the centre's.
        same += d <= 1e-3f;
        mixed += d > 0.05f;  // an edge pixel: part of the other surface's colour
        EXPECT_EQ(four.pixels[p].a, 1.0f);
    }
    // The ball's outline and the floor's edges are mixed (90 pixels here); the
    // pixels inside a surface keep the single-sample colour (up to the fog's depth).
    EXPECT_GT(mixed, 60u);
    EXPECT_GT(same, one.pixels.size() / 2);
}

// A shadow boundary inside a surface is no geometric edge, so coverage alone leaves it as
// jagged as one sample does: the pixels along it test the light at their samples
// (shadow_edges.h) and take colours between lit and shadowed. Raster and ray-cast frames make
// the same choice there too.
TEST(RenderMsaa, ShadowEdgesMixInsideASurface) {
    for (render::RendererKind kind : {render::RendererKind::raster, render::RendererKind::raytrace}) {
        const Frame unlit_1 = render(1, kind, render::ShadowMode::none);
        const Frame unlit_4 = render(4, kind, render::ShadowMode::none);
        const Frame shadowed_1 = render(1, kind, render::ShadowMode::rays);
        const Frame shadowed_4 = render(4, kind, render::ShadowMode::rays);
        size_t inside = 0, between = 0;
        for (size_t p = 0; p < unlit_1.pixels.size(); ++p) {
            // Inside a surface: multisampling changes nothing there without shadows.
            if (max_difference(unlit_1.pixels[p], unlit_4.pixels[p]) > 1e-3f) continue;
            ++inside;
            const float lit = unlit_4.pixels[p].g, dark = shadowed_1.pixels[p].g, mixed = shadowed_4.pixels[p].g;
            // Lit in one sample but partly shadowed at four, or the other way round.
            between += std::min(std::abs(mixed - lit), std::abs(mixed - dark)) > 0.02f &&
                       mixed < std::max(lit, dark) && mixed > 0.0f;
        }
        EXPECT_GT(inside, unlit_1.pixels.size() / 2) << int(kind);
        EXPECT_GT(between, 20u) << int(kind) << ": the ball's shadow on the floor has soft pixels";
    }
    const Frame raster = render(4, render::RendererKind::raster, render::ShadowMode::rays);
    const Frame rays = render(4, render::RendererKind::raytrace, render::ShadowMode::rays);
    size_t differ = 0;
    for (size_t p = 0; p < raster.pixels.size(); ++p) differ += max_difference(raster.pixels[p], rays.pixels[p]) > 2.0f / 255;
    EXPECT_LT(differ, raster.pixels.size() / 100);
}

TEST(RenderMsaa, SameForAnyThreadCount) {
    for (render::RendererKind kind : {render::RendererKind::raster, render::RendererKind::raytrace}) {
        const Frame a = render(4, kind, render::ShadowMode::rays, 1);
        const Frame b = render(4, kind, render::ShadowMode::rays, 2);
        ASSERT_EQ(a.pixels.size(), b.pixels.size());
        EXPECT_EQ(0, std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(glm::vec4))) << int(kind);
    }
}

TEST(RenderMsaa, RasterAndRaysAgreeSampleForSample) {
    const Frame raster = render(4, render::RendererKind::raster, render::ShadowMode::none);
    const Frame rays = render(4, render::RendererKind::raytrace, render::ShadowMode::none);
    size_t differ = 0;
    for (size_t p = 0; p < raster.pixels.size(); ++p) differ += max_difference(raster.pixels[p], rays.pixels[p]) > 2.0f / 255;
    EXPECT_LT(differ, raster.pixels.size() / 100);
}

// Marched silhouettes against the background mix like rasterized ones (the pass samples the
// edge pixels at the same positions), whichever renderer found the visibility and whatever the
// thread count; the insides keep their one-sample colour.
TEST(RenderMsaa, MarchedSilhouettesMix) {
    const Frame one = render(1, render::RendererKind::raster, render::ShadowMode::none, 0, kBalls);
    const Frame four = render(4, render::RendererKind::raster, render::ShadowMode::none, 0, kBalls);
    const glm::vec4 background(0.2f, 0.3f, 0.9f, 1.0f);
    size_t same = 0, mixed = 0, surface = 0;
    for (size_t p = 0; p < one.pixels.size(); ++p) {
        same += one.pixels[p] == four.pixels[p];
        surface += one.pixels[p] != background;
        mixed += max_difference(one.pixels[p], four.pixels[p]) > 0.05f;
    }
    EXPECT_GT(surface, 500u);
    EXPECT_GT(mixed, 40u);
    EXPECT_GT(same, one.pixels.size() * 3 / 4);
    for (render::RendererKind kind : {render::RendererKind::raster, render::RendererKind::raytrace}) {
        const Frame a = render(4, kind, render::ShadowMode::none, 1, kBalls);
        EXPECT_EQ(0, std::memcmp(a.pixels.data(), four.pixels.data(), a.pixels.size() * sizeof(glm::vec4))) << int(kind);
    }
}

TEST(RenderMsaa, RejectsBadSampleCounts) {
    std::vector<std::string> warnings;
    render::AnimatedScene scene = scene_file::build_scene(scene_file::parse_scene(kBall, "ball.json", warnings));
    for (int bad : {0, 2, 3, 32})
        EXPECT_THROW(render::FrameRenderer(scene, 16, 16, render::RendererKind::raster, render::ShadowMode::none, bad),
                     std::invalid_argument);
    const std::string json = std::string(kBall).insert(1, R"("render": {"samples": 5},)");
    EXPECT_THROW(scene_file::parse_scene(json, "ball.json", warnings), std::exception);
    const std::string good = std::string(kBall).insert(1, R"("render": {"samples": 8},)");
    EXPECT_EQ(scene_file::parse_scene(good, "ball.json", warnings).samples, 8);
}

}  // namespace
