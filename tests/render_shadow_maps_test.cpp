// render::build_shadow_maps: every light's maps with its own settings, rendered again in place
// on the next frame, giving the bytes a fresh build gives; cascades in which nothing moved
// are kept, and still equal a fresh build.
#include <gtest/gtest.h>

#include <vector>

#include "raster/render/frame_renderer.h"
#include "raster/workloads/sphere_grid.h"

namespace tessera::render {
namespace {

// A ground with a raised square over it, the square shifted by `dx` (an animated caster),
// and a second square far from the camera, shifted by `far_dx`.
Mesh scene_at(float dx, float far_dx = 0.0f) {
    Mesh mesh;
    workloads::append_ground(mesh, 0.0f, 0.0f, 0.0f, 12.0f, 6);
    workloads::append_ground(mesh, dx, 0.5f, 0.8f, 1.0f, 2);
    workloads::append_ground(mesh, 2.0f + far_dx, -9.0f, 0.6f, 1.0f, 2);
    return mesh;
}

Camera camera_at(float x) {
    Camera c;
    c.eye = {x, 2.0f, 5.0f};
    c.lookat = {0.0f, 0.0f, 0.0f};
    c.aspect = 16.0f / 9.0f;
    c.near = 0.1f;
    c.far = 40.0f;
    return c;
}

std::vector<scene::Light> two_lights() {
    std::vector<scene::Light> lights = {scene::directional_light({-0.5f, 1.0f, 0.3f}, glm::vec3(0.1f), glm::vec3(1.0f)),
                                        scene::point_light({1.0f, 4.0f, 1.0f}, glm::vec3(0.0f), glm::vec3(1.0f))};
    lights[0].shadow_map.resolution = 256;
    lights[0].shadow_map.cascades = 3;
    lights[1].shadow_map.resolution = 128;
    lights[1].shadow_map.cascades = 2;
    return lights;
}

void expect_same_maps(const std::vector<shadow::ShadowMap>& a, const std::vector<shadow::ShadowMap>& b) {
    ASSERT_EQ(a.size(), b.size());
    for (size_t l = 0; l < a.size(); ++l) {
        ASSERT_EQ(a[l].cascade_count(), b[l].cascade_count());
        EXPECT_EQ(a[l].light(), b[l].light());
        EXPECT_EQ(a[l].splits(), b[l].splits());
        for (int c = 0; c < a[l].cascade_count(); ++c) {
            EXPECT_EQ(a[l].view_projection(c), b[l].view_projection(c)) << "light " << l << " cascade " << c;
            const std::span<const float> da = a[l].depth(c), db = b[l].depth(c);
            ASSERT_EQ(da.size(), db.size());
            size_t differ = 0, covered = 0;
            for (size_t i = 0; i < da.size(); ++i) {
                differ += da[i] != db[i];
                covered += da[i] < 1.0f;
            }
            EXPECT_EQ(differ, 0u) << "light " << l << " cascade " << c;
            EXPECT_GT(covered, 0u) << "light " << l << " cascade " << c;
        }
    }
}

TEST(BuildShadowMaps, OneMapPerLightWithItsSettings) {
    pipeline::Rasterizer rasterizer;
    const std::vector<scene::Light> lights = two_lights();
    std::vector<shadow::ShadowMap> maps;
    build_shadow_maps(rasterizer, scene_at(0.0f), lights, camera_at(0.0f), maps);
    ASSERT_EQ(maps.size(), 2u);
    for (size_t l = 0; l < 2; ++l) {
        EXPECT_EQ(maps[l].options(), lights[l].shadow_map);
        EXPECT_EQ(maps[l].cascade_count(), lights[l].shadow_map.cascades);
        EXPECT_EQ(maps[l].light(), shadow_target(lights[l]));
        EXPECT_EQ(maps[l].depth(0).size(), size_t(lights[l].shadow_map.resolution) * size_t(lights[l].shadow_map.resolution));
    }
}

TEST(BuildShadowMaps, NextFrameRendersInPlaceAsAFreshBuild) {
    pipeline::Rasterizer rasterizer;
    const std::vector<scene::Light> lights = two_lights();
    std::vector<shadow::ShadowMap> reused;
    build_shadow_maps(rasterizer, scene_at(0.0f), lights, camera_at(0.0f), reused);
    const float* memory = reused[0].depth(0).data();
    // The caster and the camera moved: the second frame's maps, in the first frame's memory.
    build_shadow_maps(rasterizer, scene_at(0.7f), lights, camera_at(1.5f), reused);
    EXPECT_EQ(reused[0].depth(0).data(), memory);
    std::vector<shadow::ShadowMap> fresh;
    pipeline::Rasterizer other;
    build_shadow_maps(other, scene_at(0.7f), lights, camera_at(1.5f), fresh);
    expect_same_maps(reused, fresh);
}

int drawn(const std::vector<shadow::ShadowMap>& maps) {
    int n = 0;
    for (const shadow::ShadowMap& m : maps) n += m.cascades_rendered();
    return n;
}

TEST(BuildShadowMaps, OnlyCascadesWhereSomethingMovedAreDrawnAgain) {
    pipeline::Rasterizer rasterizer;
    const std::vector<scene::Light> lights = two_lights();
    const Camera camera = camera_at(0.3f);
    std::vector<shadow::ShadowMap> maps;
    build_shadow_maps(rasterizer, scene_at(0.0f), lights, camera, maps);
    EXPECT_EQ(drawn(maps), 5);
    // Nothing moved: every cascade kept.
    build_shadow_maps(rasterizer, scene_at(0.0f), lights, camera, maps);
    EXPECT_EQ(drawn(maps), 0);
    // The far square moved: the point light's cascades (which draw everything) and the
    // directional light's far cascade are drawn, its near ones kept.
    build_shadow_maps(rasterizer, scene_at(0.0f, 0.25f), lights, camera, maps);
    EXPECT_EQ(maps[1].cascades_rendered(), 2);
    EXPECT_GE(maps[0].cascades_rendered(), 1);
    EXPECT_LT(maps[0].cascades_rendered(), 3);
    pipeline::Rasterizer other;
    std::vector<shadow::ShadowMap> fresh;
    build_shadow_maps(other, scene_at(0.0f, 0.25f), lights, camera, fresh);
    expect_same_maps(maps, fresh);
    // The near square moved and then the camera: all again equal to fresh builds.
    build_shadow_maps(rasterizer, scene_at(0.4f, 0.25f), lights, camera, maps);
    EXPECT_GE(drawn(maps), 3);
    fresh.clear();
    build_shadow_maps(other, scene_at(0.4f, 0.25f), lights, camera, fresh);
    expect_same_maps(maps, fresh);
    build_shadow_maps(rasterizer, scene_at(0.4f, 0.25f), lights, camera_at(0.9f), maps);
    fresh.clear();
    build_shadow_maps(other, scene_at(0.4f, 0.25f), lights, camera_at(0.9f), fresh);
    expect_same_maps(maps, fresh);
    // Other triangles (the same positions): everything drawn.
    Mesh fewer = scene_at(0.4f, 0.25f);
    fewer.indices.resize(fewer.indices.size() - 3);
    build_shadow_maps(rasterizer, fewer, lights, camera_at(0.9f), maps);
    EXPECT_EQ(drawn(maps), 5);
}

TEST(BuildShadowMaps, ChangedSettingsBuildAnew) {
    pipeline::Rasterizer rasterizer;
    std::vector<scene::Light> lights = two_lights();
    std::vector<shadow::ShadowMap> maps;
    build_shadow_maps(rasterizer, scene_at(0.0f), lights, camera_at(0.0f), maps);
    lights[1].shadow_map.resolution = 64;
    lights[1].shadow_map.pcf_radius = 0;
    build_shadow_maps(rasterizer, scene_at(0.0f), lights, camera_at(0.0f), maps);
    ASSERT_EQ(maps.size(), 2u);
    EXPECT_EQ(maps[1].options(), lights[1].shadow_map);
    EXPECT_EQ(maps[1].depth(0).size(), 64u * 64u);
    lights.pop_back();
    build_shadow_maps(rasterizer, scene_at(0.0f), lights, camera_at(0.0f), maps);
    EXPECT_EQ(maps.size(), 1u);
}

}  // namespace
}  // namespace tessera::render
