// Alpha-tested surfaces (glTF 2.0 alphaMode MASK, scene::Material::masked) in both renderers:
// the cut-out part shows what lies behind, the nearest surviving surface wins whatever the
// submission order, blended surfaces behind a masked one stay hidden, and the raster and
// ray-cast renderers give the same picture.
#include <gtest/gtest.h>

#include <memory>

#include "raster/render/frame_renderer.h"
#include "shading_scenes.h"

using namespace tessera;

namespace {

// A 2 x 2 square at depth z (facing +z) in one material.
scene::Object square(const std::string& name, float z, uint32_t material) {
    auto mesh = std::make_shared<Mesh>();
    mesh->positions = {{-1, -1, z}, {1, -1, z}, {1, 1, z}, {-1, 1, z}};
    mesh->normals.assign(4, glm::vec3(0, 0, 1));
    mesh->uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    mesh->indices = {0, 1, 2, 0, 2, 3};
    return {name, mesh, material, {}, {}};
}

using test::flat_colour;

// Seen head-on, lit so that a surface facing the camera shows exactly its kd: the masked front
// square (white, its texture transparent on the left half) is submitted first, then a masked
// blue square behind it (alpha 1 everywhere), a blended green one behind that, and an opaque
// red one at the back.
render::AnimatedScene layered_scene() {
    scene::Scene s;
    s.camera.eye = {0, 0, 4};
    s.camera.fovy_deg = 40.0f;
    s.camera.near = 1.0f;
    s.camera.far = 10.0f;
    s.lights = {scene::directional_light({0, 0, 1}, glm::vec3(0.25f), glm::vec3(0.75f))};
    s.background.colour = glm::vec3(0.0f);
    // 2 x 1 texels, nearest: alpha 0 left of u = 0.5, 1 right of it.
    s.textures.emplace_back(2, 1, std::vector<glm::vec4>{{1, 1, 1, 0}, {1, 1, 1, 1}});
    scene::Material cut = flat_colour(glm::vec3(1.0f));
    cut.diffuse_texture = 0;
    cut.filter = texture::TextureFilter::nearest;
    cut.alpha_cutoff = 0.5f;
    scene::Material blue = flat_colour({0, 0, 1});
    blue.alpha_cutoff = 0.5f;
    scene::Material green = flat_colour({0, 1, 0});
    green.opacity = 0.5f;
    s.materials = {cut, blue, green, flat_colour({1, 0, 0})};
    s.objects = {square("front", 0.0f, 0), square("blue", -0.25f, 1), square("green", -0.4f, 2),
                 square("red", -0.5f, 3)};
    return render::still_scene(std::move(s));
}

Frame render_layers(render::RendererKind renderer) {
    render::AnimatedScene scene = layered_scene();
    render::FrameRenderer frames(scene, 96, 64, renderer, render::ShadowMode::none);
    return frames.render(0.0f);
}

TEST(AlphaMask, NearestSurvivingSurfaceWinsInBothRenderers) {
    for (const auto renderer : {render::RendererKind::raster, render::RendererKind::raytrace}) {
        const Frame frame = render_layers(renderer);
        // Pixels well inside the squares (they cover x in [~20, ~76) at 96 x 64): left of the
        // centre the front square is cut away and the blue one shows; right of it, white.
        for (int y = 24; y < 40; ++y) {
            for (int x = 30; x < 44; ++x) {
                const glm::vec4 c = frame.at(x, y);
                EXPECT_NEAR(c.b, 1.0f, 1e-5f) << x << "," << y;
                EXPECT_NEAR(c.r, 0.0f, 1e-5f) << x << "," << y;  // neither red nor white
                EXPECT_NEAR(c.g, 0.0f, 1e-5f) << x << "," << y;  // the green glass is behind blue
            }
            for (int x = 52; x < 66; ++x) EXPECT_NEAR(frame.at(x, y).r, 1.0f, 1e-5f) << x << "," << y;
        }
    }
}

TEST(AlphaMask, RasterAndRayCastAgreeUpToEdges) {
    const Frame raster = render_layers(render::RendererKind::raster);
    const Frame rays = render_layers(render::RendererKind::raytrace);
    size_t differ = 0;
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 96; ++x) differ += glm::any(glm::greaterThan(glm::abs(raster.at(x, y) - rays.at(x, y)),
                                                                         glm::vec4(1.0f / 255.0f)));
    EXPECT_LE(differ, size_t(96 * 64 / 100)) << "pixels that differ";
}

}  // namespace
