// Embree shadow rays: occluded and lit points, packet widths agreeing with single rays, no
// self-shadowing on a plane, and the per-pixel light mask over a ray-cast frame.
#include <gtest/gtest.h>

#include <filesystem>
#include <vector>

#include "raster/embree/ray_cast.h"
#include "raster/embree/scene.h"
#include "raster/embree/shadow_rays.h"
#include "raster/io/image_io.h"
#include "raster/shadow/mask_compare.h"
#include "raster/shadow/light_mask.h"
#include "raster/workloads/sphere_grid.h"

namespace tessera::embree {
namespace {

// A ground square (y = 0, 10 x 10) under a 1 x 1 occluder at y = 1 centred over the origin.
Mesh ground_and_occluder() {
    Mesh mesh;
    workloads::append_ground(mesh, 0.0f, 0.0f, 0.0f, 10.0f, 4);
    workloads::append_ground(mesh, 0.0f, 0.0f, 1.0f, 1.0f, 1);
    reserve_ray_padding(mesh);
    return mesh;
}

const glm::vec3 kLightAbove{0.0f, 5.0f, 0.0f};

class ShadowRayWidths : public ::testing::TestWithParam<RayPacket> {};

TEST_P(ShadowRayWidths, PointUnderOccluderIsShadowedAndBesideItLit) {
    const Mesh mesh = ground_and_occluder();
    const RayScene scene(default_ray_device(), mesh);
    shadow::SurfacePoints points;
    points.pixel = {0, 1, 2};
    points.position = {{0.0f, 0.0f, 0.0f}, {2.0f, 0.0f, 0.0f}, {0.3f, 0.0f, -0.3f}};
    points.normal.assign(3, {0.0f, 1.0f, 0.0f});
    std::vector<uint8_t> visible(3, 0);
    const glm::vec3 lights[] = {kLightAbove};
    trace_shadow_rays(scene, points, lights, visible, GetParam());
    EXPECT_EQ(visible[0], 0) << "under the occluder";
    EXPECT_EQ(visible[1], 1) << "beside the occluder";
    EXPECT_EQ(visible[2], 0) << "under the occluder, off centre";
}

TEST_P(ShadowRayWidths, SurfaceFacingAwayIsNotLitAndNotTraced) {
    const Mesh mesh = ground_and_occluder();
    const RayScene scene(default_ray_device(), mesh);
    shadow::SurfacePoints points;
    points.pixel = {0};
    points.position = {{3.0f, 0.0f, 3.0f}};
    points.normal = {{0.0f, -1.0f, 0.0f}};  // seen from below: the light is behind it
    std::vector<uint8_t> visible(1, 0);
    const glm::vec3 lights[] = {kLightAbove};
    trace_shadow_rays(scene, points, lights, visible, GetParam());
    EXPECT_EQ(visible[0], 0);
}

INSTANTIATE_TEST_SUITE_P(Embree, ShadowRayWidths,
                         ::testing::Values(RayPacket::single, RayPacket::x8, RayPacket::x16));

TEST(EmbreeShadowMask, FlatPlaneHasNoSelfShadowingAtAnyAngle) {
    Mesh mesh;
    workloads::append_ground(mesh, 0.0f, 0.0f, 0.0f, 40.0f, 64);
    reserve_ray_padding(mesh);
    const RayScene scene(default_ray_device(), mesh);
    Camera camera;
    camera.eye = {0.0f, 3.0f, 12.0f};
    camera.lookat = {0.0f, 0.0f, 0.0f};
    const glm::mat4 vp = camera.view_projection();
    VisibilityBuffer vis;
    cast_primary_rays(scene, vp, 192, 108, vis);
    // One light high up, one grazing at 2 degrees over the far edge.
    const glm::vec3 lights[] = {{1.0f, 20.0f, 2.0f}, {0.0f, 1.4f, -40.0f}};
    const shadow::LightMask mask =
        shadow::compute_light_mask(vis, mesh, vp, lights, shadow_ray_test(scene));
    size_t covered = 0;
    for (size_t p = 0; p < mask.bits.size(); ++p) {
        if (vis.triangle[p] == kNoTriangle) continue;
        ++covered;
        ASSERT_EQ(mask.bits[p], 3) << "pixel " << p;
    }
    EXPECT_GT(covered, mask.bits.size() / 3);
}

TEST(EmbreeShadowMask, OccluderShadowLandsUnderItInTheImage) {
    const Mesh mesh = ground_and_occluder();
    const RayScene scene(default_ray_device(), mesh);
    Camera camera;
    camera.eye = {0.0f, 6.0f, 6.0f};
    camera.lookat = {0.0f, 0.0f, 0.0f};
    camera.aspect = 1.0f;
    const glm::mat4 vp = camera.view_projection();
    VisibilityBuffer vis;
    cast_primary_rays(scene, vp, 128, 128, vis);
    const glm::vec3 lights[] = {kLightAbove};
    const shadow::LightMask mask =
        shadow::compute_light_mask(vis, mesh, vp, lights, shadow_ray_test(scene));
    const auto pixel_of = [&](const glm::vec3& p) {
        const glm::vec4 clip = vp * glm::vec4(p, 1.0f);
        const int x = int((clip.x / clip.w * 0.5f + 0.5f) * 128);
        const int y = int((0.5f - clip.y / clip.w * 0.5f) * 128);
        return size_t(y) * 128 + size_t(x);
    };
    // Seen from this camera the ground point straight under the occluder is hidden by it;
    // the ground just behind it (from the camera) is in its shadow and visible.
    const size_t behind = pixel_of({0.0f, 0.0f, -0.45f});
    ASSERT_LT(vis.triangle[behind], 32u) << "expected the ground at this pixel";
    EXPECT_EQ(mask.bits[behind], 0);
    const size_t beside = pixel_of({2.5f, 0.0f, 0.0f});
    ASSERT_LT(vis.triangle[beside], 32u);
    EXPECT_EQ(mask.bits[beside], 1);
    const size_t top = pixel_of({0.2f, 1.0f, 0.2f});
    ASSERT_GE(vis.triangle[top], 32u) << "expected the occluder at this pixel";
    EXPECT_EQ(mask.bits[top], 1);
}

TEST(EmbreeShadowMask, PacketsAgreeWithSingleRaysOnTheSphereGrid) {
    const workloads::SphereGridScene grid = workloads::make_sphere_grid(20000);
    const RayScene scene(default_ray_device(), grid.mesh);
    const glm::mat4 vp = grid.camera.view_projection();
    VisibilityBuffer vis;
    cast_primary_rays(scene, vp, 240, 135, vis);
    const glm::vec3 lights[] = {grid.light, {-3.0f, 2.0f, 1.0f}};
    const auto single = shadow::compute_light_mask(vis, grid.mesh, vp, lights,
                                                   shadow_ray_test(scene, RayPacket::single));
    const auto x16 = shadow::compute_light_mask(vis, grid.mesh, vp, lights,
                                                shadow_ray_test(scene, RayPacket::x16));
    const auto x8 = shadow::compute_light_mask(vis, grid.mesh, vp, lights,
                                               shadow_ray_test(scene, RayPacket::x8));
    EXPECT_EQ(single.bits, x16.bits);
    EXPECT_EQ(single.bits, x8.bits);
    size_t shadowed = 0;
    for (size_t p = 0; p < vis.triangle.size(); ++p)
        shadowed += vis.triangle[p] != kNoTriangle && (single.bits[p] & 1) == 0;
    EXPECT_GT(shadowed, 500u) << "the scene should cast shadows";
}

TEST(EmbreeShadowMask, MoreLightsThanMaskBitsIsRejected) {
    const Mesh mesh = ground_and_occluder();
    const RayScene scene(default_ray_device(), mesh);
    VisibilityBuffer vis;
    vis.reset(4, 4);
    const std::vector<glm::vec3> lights(9, kLightAbove);
    EXPECT_THROW(shadow::compute_light_mask(vis, mesh, glm::mat4(1.0f), lights,
                                            shadow_ray_test(scene)),
                 std::invalid_argument);
}


TEST(ShadowMaskCompare, CountsDisagreementsAndExclusions) {
    VisibilityBuffer vis;
    vis.reset(4, 2);
    for (size_t p = 0; p < 7; ++p) vis.triangle[p] = 0;  // pixel 7 is empty
    shadow::LightMask a{4, 2, {1, 1, 0, 3, 2, 0, 1, 1}};
    shadow::LightMask b{4, 2, {1, 0, 0, 3, 1, 1, 1, 0}};
    shadow::LightMask exclude{4, 2, {0, 0, 0, 0, 0, 1, 0, 0}};
    const auto plain = shadow::compare_light_masks(a, b, vis);
    EXPECT_EQ(plain.compared, 7u);
    EXPECT_EQ(plain.differ, 3u);      // pixels 1, 4, 5 (7 is empty)
    EXPECT_EQ(plain.only_a_lit, 2u);  // 1 and 4
    EXPECT_EQ(plain.only_b_lit, 2u);  // 4 and 5
    const auto trimmed = shadow::compare_light_masks(a, b, vis, &exclude);
    EXPECT_EQ(trimmed.compared, 6u);
    EXPECT_EQ(trimmed.excluded, 1u);
    EXPECT_EQ(trimmed.differ, 2u);
    EXPECT_DOUBLE_EQ(trimmed.agreement(), 4.0 / 6.0);
    shadow::LightMask small{2, 2, {0, 0, 0, 0}};
    EXPECT_THROW(shadow::compare_light_masks(a, small, vis), std::invalid_argument);

    const auto path = std::filesystem::path(::testing::TempDir()) / "embree_mask_diff.png";
    shadow::write_mask_diff(path, a, b, vis, &exclude);
    const io::FloatImage image = io::read_image(path);
    ASSERT_EQ(image.width, 4);
    EXPECT_EQ(image.at(0, 0, 0), image.at(0, 0, 2));  // agree, lit: grey
    EXPECT_GT(image.at(0, 0, 0), 0.8f);
    EXPECT_EQ(image.at(1, 0, 0), 1.0f);  // only a lit: red
    EXPECT_EQ(image.at(1, 0, 2), 0.0f);
    EXPECT_EQ(image.at(0, 1, 0), 1.0f);  // pixel 4: both ways: magenta
    EXPECT_EQ(image.at(0, 1, 2), 1.0f);
    EXPECT_EQ(image.at(3, 1, 0), 0.0f);  // empty: black
    std::filesystem::remove(path);
}

TEST(ShadowMaskCompare, GrazingLightsMarksOnlyNearTangentLights) {
    shadow::SurfacePoints points;
    points.pixel = {0};
    points.position = {{0.0f, 0.0f, 0.0f}};
    points.normal = {{0.0f, 1.0f, 0.0f}};
    const glm::vec3 lights[] = {{10.0f, 0.5f, 0.0f}, {0.0f, 10.0f, 0.0f}, {10.0f, -0.5f, 0.0f}};
    std::vector<uint8_t> visible(1, 0);
    shadow::grazing_lights(0.1f)(points, lights, visible);
    EXPECT_EQ(visible[0], 1);  // 2.9 degrees above the plane; overhead and below are not
}

}  // namespace
}  // namespace tessera::embree
