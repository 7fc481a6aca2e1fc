// Cascaded shadow maps (shadow/cascades.h, shadow/shadow_map.h): the practical split scheme,
// each cascade covering its slice of the view frustum, texel snapping keeping a distant
// light's projection on one world grid as the camera moves, a contact shadow surviving the
// bias, the SIMD lookup across cascades, and bad settings.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "raster/embree/scene.h"
#include "raster/geometry/box.h"
#include "raster/pipeline/rasterizer.h"
#include "raster/shadow/cascades.h"
#include "raster/shadow/shadow_map.h"
#include "raster/workloads/sphere_grid.h"

namespace tessera::shadow {
namespace {

Camera test_camera() {
    Camera c;
    c.eye = {0.3f, 1.4f, 3.2f};
    c.lookat = {-0.1f, 0.0f, 0.0f};
    c.fovy_deg = 45.0f;
    c.aspect = 16.0f / 9.0f;
    c.near = 0.1f;
    c.far = 60.0f;
    return c;
}

// Texel coordinates of a world point in a projection's map.
glm::vec3 texel_of(const LightProjection& p, const glm::vec3& world, int resolution) {
    const glm::vec4 clip = p.view_projection * glm::vec4(world, 1.0f);
    const glm::vec3 ndc = glm::vec3(clip) / clip.w;
    return {(ndc.x * 0.5f + 0.5f) * float(resolution), (0.5f - ndc.y * 0.5f) * float(resolution), ndc.z};
}

TEST(Cascades, PracticalSplitsBlendLogarithmicAndUniform) {
    const std::vector<float> uniform = cascade_splits(1.0f, 101.0f, 4, 0.0f);
    const std::vector<float> logarithmic = cascade_splits(1.0f, 10000.0f, 4, 1.0f);
    const std::vector<float> blend = cascade_splits(0.5f, 40.0f, 5, 0.8f);
    ASSERT_EQ(uniform.size(), 5u);
    for (int i = 0; i <= 4; ++i) {
        EXPECT_NEAR(uniform[size_t(i)], 1.0f + 25.0f * float(i), 1e-4f);
        EXPECT_NEAR(logarithmic[size_t(i)], std::pow(10.0f, float(i)), 1e-3f * std::pow(10.0f, float(i)));
    }
    ASSERT_EQ(blend.size(), 6u);
    EXPECT_EQ(blend.front(), 0.5f);
    EXPECT_EQ(blend.back(), 40.0f);
    for (size_t i = 1; i < blend.size(); ++i) EXPECT_LT(blend[i - 1], blend[i]);
}

TEST(Cascades, EachCascadeCoversItsFrustumSlice) {
    const Camera camera = test_camera();
    Bounds scene;
    scene.lo = {-20.0f, -1.0f, -20.0f};
    scene.hi = {20.0f, 1.5f, 20.0f};
    const auto [near, far] = shadowed_depths(camera, scene);
    EXPECT_EQ(near, camera.near);
    EXPECT_GT(far, 20.0f);
    EXPECT_LE(far, camera.far);
    const std::vector<float> splits = cascade_splits(near, far, 4, 0.8f);
    for (const bool distant : {true, false})
        for (size_t c = 0; c + 1 < splits.size(); ++c) {
            const Sphere sphere = slice_sphere(camera, splits[c], splits[c + 1]);
            const LightProjection p =
                distant ? fit_distant_light({-0.55f, 0.42f, -0.72f}, sphere, scene, 1024)
                        : fit_point_light({3.0f, 8.0f, 2.0f}, sphere, scene, 1024);
            for (const glm::vec3& corner : frustum_slice(camera, splits[c], splits[c + 1])) {
                EXPECT_LE(glm::length(corner - sphere.centre), sphere.radius * (1.0f + 1e-5f));
                const glm::vec3 t = texel_of(p, corner, 1024);
                EXPECT_GE(t.x, 0.0f) << "cascade " << c << (distant ? " distant" : " point");
                EXPECT_LE(t.x, 1024.0f) << "cascade " << c;
                EXPECT_GE(t.y, 0.0f) << "cascade " << c;
                EXPECT_LE(t.y, 1024.0f) << "cascade " << c;
                EXPECT_GE(t.z, -1.0f) << "cascade " << c;
                EXPECT_LE(t.z, 1.0f) << "cascade " << c;
            }
            // Casters anywhere in the scene's depth range towards the light are in the map.
            if (distant) {
                const glm::vec3 above = sphere.centre + 3.0f * glm::normalize(glm::vec3(-0.55f, 0.42f, -0.72f));
                EXPECT_GE(texel_of(p, above, 1024).z, -1.0f);
            }
        }
}

TEST(Cascades, TexelSnappingKeepsTheGridUnderSmallCameraMoves) {
    Bounds scene;
    scene.lo = {-20.0f, -1.0f, -20.0f};
    scene.hi = {20.0f, 1.5f, 20.0f};
    const glm::vec3 towards_light{-0.55f, 0.42f, -0.72f};
    const std::vector<glm::vec3> points = {{0.0f, 0.0f, 0.0f}, {0.37f, 0.2f, -0.61f}, {-1.1f, 0.05f, 0.4f}};
    const Camera a = test_camera();
    for (const glm::vec3 move : {glm::vec3(0.0031f, 0.0f, 0.0f), glm::vec3(0.0f, 0.0013f, -0.0047f),
                                 glm::vec3(0.021f, -0.008f, 0.013f)}) {
        Camera b = a;
        b.eye += move;
        b.lookat += move;
        for (const auto& [d0, d1] : {std::pair{0.1f, 1.5f}, std::pair{1.5f, 4.0f}}) {
            const Sphere sa = slice_sphere(a, d0, d1), sb = slice_sphere(b, d0, d1);
            EXPECT_EQ(sa.radius, sb.radius);  // computed in the camera's own space
            const LightProjection pa = fit_distant_light(towards_light, sa, scene, 2048);
            const LightProjection pb = fit_distant_light(towards_light, sb, scene, 2048);
            EXPECT_EQ(pa.texel_size, pb.texel_size);
            for (const glm::vec3& p : points) {
                // The same world point sits at the same place within its texel: the maps
                // differ by a whole-texel shift.
                const glm::vec3 ta = texel_of(pa, p, 2048), tb = texel_of(pb, p, 2048);
                const float dx = ta.x - tb.x, dy = ta.y - tb.y;
                EXPECT_NEAR(dx, std::round(dx), 2e-3f) << "move " << move.x << "," << move.y << "," << move.z;
                EXPECT_NEAR(dy, std::round(dy), 2e-3f);
            }
        }
        // Turning the camera (about its eye) keeps the cascades' sizes too.
        Camera turned = a;
        turned.lookat = a.eye + glm::mat3(glm::rotate(glm::mat4(1.0f), 0.05f, glm::vec3(0, 1, 0))) * (a.lookat - a.eye);
        EXPECT_EQ(slice_sphere(a, 1.5f, 4.0f).radius, slice_sphere(turned, 1.5f, 4.0f).radius);
    }
    // The shadowed range ends on a grid of steps of 2^(1/8), so a small move rarely changes
    // it: check the ends lie on it.
    const auto [near, far] = shadowed_depths(a, scene);
    const float k = 8.0f * std::log2(far / near);
    EXPECT_NEAR(k, std::round(k), 1e-3f);
}

// A flat slab 5 cm thick lying on a 40 m ground, lit from 45 degrees: the ground within a
// few centimetres of its edge is in its shadow.
Mesh slab_on_ground() {
    Mesh mesh;
    workloads::append_ground(mesh, 0.0f, 0.0f, 0.0f, 40.0f, 8);
    Mesh slab = geometry::box_mesh({0.5f, 0.025f, 0.5f});
    const uint32_t base = uint32_t(mesh.positions.size());
    for (const glm::vec3& p : slab.positions) mesh.positions.push_back(p + glm::vec3(0.0f, 0.025f, 0.0f));
    for (uint32_t i : slab.indices) mesh.indices.push_back(base + i);
    mesh.normals.clear();
    mesh.uvs.clear();
    mesh.tangents.clear();
    embree::reserve_ray_padding(mesh);
    return mesh;
}

TEST(ShadowMapCascades, AContactShadowSurvivesTheBias) {
    const Mesh mesh = slab_on_ground();
    const glm::vec3 towards{1.0f, 1.0f, 0.3f};
    const ShadowLight light(glm::normalize(towards) * 1.0e4f, true);
    const glm::vec3 up{0.0f, 1.0f, 0.0f};
    // (-0.52, 0, 0) sees the light through the slab's top (y = 0.05 at x = -0.47); (-0.6, 0, 0)
    // passes beside it.
    const glm::vec3 in_contact{-0.52f, 0.0f, 0.0f}, beside{-0.6f, 0.0f, 0.0f};
    pipeline::Rasterizer rasterizer;
    const ShadowMap fitted(rasterizer, mesh, light, test_camera(), ShadowMapOptions{});
    EXPECT_FALSE(fitted.lit(in_contact, up));
    EXPECT_TRUE(fitted.lit(beside, up));
    EXPECT_TRUE(fitted.lit({0.0f, 0.05f, 0.0f}, up)) << "the slab's own top";
    EXPECT_LT(fitted.cascade_of(in_contact, up), fitted.cascade_count());
    // One map of the same size over the whole ground: its texels are ~3 cm, and the bias
    // that keeps its acne away lifts the receiver over the slab.
    const ShadowMap whole(rasterizer, mesh, light, ShadowMapOptions{});
    EXPECT_TRUE(whole.lit(in_contact, up));
}

TEST(ShadowMapCascades, SimdLookupEqualsScalarReferenceInEveryCascade) {
    const Mesh mesh = slab_on_ground();
    const Camera camera = test_camera();
    pipeline::Rasterizer rasterizer;
    ShadowMapOptions options;
    options.resolution = 256;
    const ShadowMap map(rasterizer, mesh, ShadowLight(glm::normalize(glm::vec3(1.0f, 1.0f, 0.3f)) * 1.0e4f, true),
                        camera, options);
    SurfacePoints points;
    std::vector<int> used(size_t(map.cascade_count()) + 1, 0);
    for (int i = 0; i < 4000; ++i) {
        const float x = -6.0f + 12.0f * float(i % 80) / 80.0f, z = -12.0f + 15.0f * float(i / 80) / 50.0f;
        const bool top = std::abs(x) < 0.5f && std::abs(z) < 0.5f;
        points.pixel.push_back(uint32_t(i));
        points.position.push_back({x, top ? 0.05f : 0.0f, z});
        points.normal.push_back({0.0f, 1.0f, 0.0f});
        ++used[size_t(map.cascade_of(points.position.back(), points.normal.back()))];
    }
    for (int c = 0; c < map.cascade_count(); ++c) EXPECT_GT(used[size_t(c)], 0) << "cascade " << c;
    std::vector<uint8_t> simd(points.size(), 0), reference(points.size(), 0);
    map.mark_lit(points, 2, simd);
    map.mark_lit_reference(points, 2, reference);
    EXPECT_EQ(simd, reference);
}

TEST(ShadowMapCascades, BadSettingsAreRejected) {
    const Mesh mesh = slab_on_ground();
    pipeline::Rasterizer rasterizer;
    for (auto change : {+[](ShadowMapOptions& o) { o.cascades = 0; }, +[](ShadowMapOptions& o) { o.cascades = 9; },
                        +[](ShadowMapOptions& o) { o.split_blend = 1.5f; },
                        +[](ShadowMapOptions& o) { o.normal_offset = 100.0f; }}) {
        ShadowMapOptions options;
        change(options);
        EXPECT_THROW(ShadowMap(rasterizer, mesh, ShadowLight({0.0f, 5.0f, 0.0f}), test_camera(), options),
                     std::invalid_argument);
    }
}

}  // namespace
}  // namespace tessera::shadow
