// Comparing shadow methods on rendered frames (shadow/shadowed_pixels.h): the counting, and
// on a small scene of contact shadows, camera-fitted cascades against Embree shadow rays,
// with a threshold that the single map of before fails.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "raster/render/frame_renderer.h"
#include "raster/scene_file/scene_build.h"
#include "raster/scene_file/scene_parse.h"
#include "raster/shadow/shadowed_pixels.h"

namespace tessera::shadow {
namespace {

TEST(ShadowedPixels, CountsPixelsDarkerByMoreThanTheLevels) {
    Frame none(4, 1, glm::vec4(0.5f, 0.5f, 0.5f, 1.0f)), a = none, b = none;
    a.pixels[0] = b.pixels[0] = glm::vec4(0.1f, 0.1f, 0.1f, 1.0f);  // both
    a.pixels[1] = glm::vec4(0.2f, 0.2f, 0.2f, 1.0f);                // only a
    b.pixels[2] = glm::vec4(0.49f, 0.49f, 0.49f, 1.0f);             // 2 levels: not shadowed
    const ShadowDisagreement d = compare_shadowed_pixels(none, a, b);
    EXPECT_EQ(d.shadowed_a, 2u);
    EXPECT_EQ(d.shadowed_b, 1u);
    EXPECT_EQ(d.either, 2u);
    EXPECT_EQ(d.differ, 1u);
    EXPECT_DOUBLE_EQ(d.fraction(), 0.5);
    EXPECT_THROW(compare_shadowed_pixels(none, a, Frame(3, 1)), std::invalid_argument);
}


// A small scene where most shadows are contact shadows of thin things on a wide ground. One
// 2048^2 map over the whole ground (what --shadows map did before cascades) disagrees with
// the rays on 60% of the shadowed pixels, one map fitted to the view on 38%; the default
// four cascades on 3%, edge pixels.
constexpr const char* kContactScene = R"({
  "camera": {"eye": [0.2, 1.1, 2.6], "lookat": [0.0, 0.0, 0.0], "fov": 45, "near": 0.1, "far": 60},
  "background": {"type": "colour", "colour": [0.5, 0.6, 0.7]},
  "lights": [{"direction": [-0.6, 0.5, -0.4], "La": [0.2, 0.2, 0.2], "Le": [1, 1, 1]}],
  "materials": {"sand": {"model": "phong", "kd": [0.8, 0.6, 0.4], "ka": [0.5, 0.4, 0.3]},
                "red": {"model": "phong", "kd": [0.8, 0.1, 0.1], "ka": [0.3, 0.1, 0.1]}},
  "objects": [
    {"name": "ground", "type": "box", "material": "sand", "size": [40, 0.1, 40], "transform": {"translate": [0, -0.05, 0]}},
    {"name": "slab", "type": "box", "material": "red", "size": [0.6, 0.04, 0.5], "transform": {"translate": [-0.4, 0.02, 0.1]}},
    {"name": "rod", "type": "box", "material": "red", "size": [0.05, 0.05, 1.2], "transform": {"translate": [0.5, 0.025, -0.2]}},
    {"name": "ball", "type": "sphere", "material": "red", "radius": 0.12, "tessellation": [32, 16], "centre": [0.1, 0.12, 0.6]}
  ]
})";

double disagreement(const render::AnimatedScene& built, const ShadowMapSettings& settings) {
    render::AnimatedScene scene = built;
    for (scene::Light& l : scene.scene.lights) l.shadow_map = settings;
    Frame frames[3];
    const render::ShadowMode modes[3] = {render::ShadowMode::none, render::ShadowMode::map, render::ShadowMode::rays};
    for (int m = 0; m < 3; ++m) {
        render::FrameRenderer renderer(scene, 320, 180, render::RendererKind::raster, modes[m]);
        frames[m] = renderer.render(0.0f);
    }
    return compare_shadowed_pixels(frames[0], frames[1], frames[2]).fraction();
}

TEST(ShadowedPixels, CascadedMapsAgreeWithShadowRaysOnContactShadows) {
    std::vector<std::string> warnings;
    const render::AnimatedScene scene =
        scene_file::build_scene(scene_file::parse_scene(kContactScene, "contact scene", warnings));
    const ShadowMapSettings cascaded;
    EXPECT_LE(disagreement(scene, cascaded), 0.05);
    ShadowMapSettings single = cascaded;
    single.cascades = 1;
    EXPECT_GT(disagreement(scene, single), 0.05);
}

}  // namespace
}  // namespace tessera::shadow
