// Golden images, one per shading mode: 128 x 128 renders of a small scene compared with the
// committed PNGs in tests/data/golden (8-bit sRGB, a few levels of tolerance, a diff image
// written on failure). Visibility comes from the brute-force caster in shading_harness.h, so
// these pin down shading alone.
#include <gtest/gtest.h>

#include "shading_harness.h"
#include "shading_scenes.h"

using namespace tessera;
using namespace tessera::test;

namespace {

constexpr int kSize = 128;

void expect_golden(const scene::Scene& scene, const std::string& name) {
    std::string why;
    EXPECT_TRUE(test::matches_golden(test::render_scene(scene, kSize, kSize), name, why)) << why;
}

}  // namespace

TEST(ShadingGolden, Flat) { expect_golden(base_scene(coloured(scene::ShadingModel::flat)), "flat"); }
TEST(ShadingGolden, Gouraud) { expect_golden(base_scene(coloured(scene::ShadingModel::gouraud)), "gouraud"); }
TEST(ShadingGolden, Phong) { expect_golden(base_scene(coloured(scene::ShadingModel::phong)), "phong"); }
TEST(ShadingGolden, Toon) { expect_golden(base_scene(coloured(scene::ShadingModel::toon)), "toon"); }

TEST(ShadingGolden, TexturedDiffuse) {
    scene::Material m = coloured(scene::ShadingModel::phong);
    m.ka = m.kd = glm::vec3(1.0f);
    m.ks = glm::vec3(0.3f);
    m.diffuse_texture = 0;
    scene::Scene s = base_scene(m);
    s.textures.push_back(checker_texture());
    expect_golden(s, "textured");
}

TEST(ShadingGolden, NormalMapped) {
    scene::Material m = coloured(scene::ShadingModel::phong);
    m.kd = m.ka = glm::vec3(0.7f);
    m.normal_texture = 0;
    scene::Scene s = base_scene(m);
    s.textures.push_back(bump_map());
    expect_golden(s, "normalmap");
}

TEST(ShadingGolden, TransparentOverOpaque) { expect_golden(transparent_scene(), "transparent"); }

TEST(ShadingGolden, SkyBackground) {
    scene::Scene s = base_scene(coloured(scene::ShadingModel::phong));
    s.background.kind = scene::Background::Kind::sky;
    s.camera.eye = {0.0f, 0.3f, 3.2f};
    s.camera.lookat = {0.0f, 0.6f, 0.0f};
    expect_golden(s, "sky");
}
