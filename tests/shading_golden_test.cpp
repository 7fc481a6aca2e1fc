// Golden images, one per shading mode: 128 x 128 renders of a small scene compared with the
// committed PNGs in tests/data/golden (8-bit sRGB, a few levels of tolerance, a diff image
// written on failure). Visibility comes from the brute-force caster in shading_harness.h, so
// these pin down shading alone.
#include <gtest/gtest.h>

#include <glm/gtc/constants.hpp>

#include "raster/geometry/param_surface.h"
#include "raster/geometry/surfaces.h"
#include "shading_harness.h"
#include "shading_scenes.h"

using namespace tessera;
using namespace tessera::test;

namespace {

constexpr int kSize = 128;

void expect_golden(const Scene& scene, const std::string& name) {
    std::string why;
    EXPECT_TRUE(test::matches_golden(test::render(scene, kSize, kSize), name, why)) << why;
}

}  // namespace

TEST(ShadingGolden, Flat) { expect_golden(base_scene(coloured(ShadingModel::flat)), "flat"); }
TEST(ShadingGolden, Gouraud) { expect_golden(base_scene(coloured(ShadingModel::gouraud)), "gouraud"); }
TEST(ShadingGolden, Phong) { expect_golden(base_scene(coloured(ShadingModel::phong)), "phong"); }
TEST(ShadingGolden, Toon) { expect_golden(base_scene(coloured(ShadingModel::toon)), "toon"); }

TEST(ShadingGolden, TexturedDiffuse) {
    Material m = coloured(ShadingModel::phong);
    m.ka = m.kd = glm::vec3(1.0f);
    m.ks = glm::vec3(0.3f);
    m.diffuse_texture = 0;
    Scene s = base_scene(m);
    s.textures.push_back(checker_texture());
    expect_golden(s, "textured");
}

TEST(ShadingGolden, NormalMapped) {
    Material m = coloured(ShadingModel::phong);
    m.kd = m.ka = glm::vec3(0.7f);
    m.normal_texture = 0;
    Scene s = base_scene(m);
    s.textures.push_back(bump_map());
    expect_golden(s, "normalmap");
}

TEST(ShadingGolden, TransparentOverOpaque) {
    Scene s = base_scene(coloured(ShadingModel::phong));
    Material glass = coloured(ShadingModel::phong);
    glass.kd = glass.ka = {0.2f, 0.5f, 0.9f};
    glass.opacity = 0.4f;
    s.materials.push_back(glass);
    // A thin torus in front of the sphere: its near and far sides both blend, in order.
    s.objects.push_back(Object{"ring", std::make_shared<const Mesh>(tessellate(torus_surface(1.2f, 0.15f), 32, 8)),
                               1, {}, {}});
    s.objects[1].transform.axis = {1, 0, 0};
    s.objects[1].transform.angle = 0.5f;
    s.objects[1].transform.translation = {0, 0, 0.6f};
    expect_golden(s, "transparent");
}

TEST(ShadingGolden, SkyBackground) {
    Scene s = base_scene(coloured(ShadingModel::phong));
    s.background.kind = Background::Kind::sky;
    s.camera.eye = {0.0f, 0.3f, 3.2f};
    s.camera.lookat = {0.0f, 0.6f, 0.0f};
    expect_golden(s, "sky");
}
