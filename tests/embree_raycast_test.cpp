// Embree's primary-ray visibility against independent answers: an analytic quad, a
// brute-force double-precision ray-triangle reference, itself across packet widths and
// thread counts, and a scene with broken triangles.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>
#include <limits>
#include <optional>

#include "raster/embree/device.h"
#include "raster/core/pixel_rays.h"
#include "raster/embree/ray_cast.h"
#include "raster/embree/scene.h"
#include "raster/core/error.h"
#include "raster/workloads/sphere_grid.h"

namespace tessera::embree {
namespace {

Mesh quad_mesh(float half) {
    Mesh mesh;
    mesh.positions = {{-half, -half, 0.0f}, {half, -half, 0.0f}, {half, half, 0.0f},
                      {-half, half, 0.0f}};
    mesh.indices = {0, 1, 2, 0, 2, 3};
    reserve_ray_padding(mesh);
    return mesh;
}

Camera front_camera(float aspect) {
    Camera camera;
    camera.eye = {0.3f, -0.2f, 3.0f};
    camera.lookat = {0.0f, 0.0f, 0.0f};
    camera.aspect = aspect;
    return camera;
}

TEST(EmbreeRayCast, QuadCoverageAndDepthMatchTheAnalyticPlane) {
    const Mesh mesh = quad_mesh(0.8f);
    const RayScene scene(default_ray_device(), mesh);
    EXPECT_TRUE(scene.shares_vertices());
    const Camera camera = front_camera(4.0f / 3.0f);
    const glm::mat4 vp = camera.view_projection();
    VisibilityBuffer vis;
    cast_primary_rays(scene, vp, 160, 120, vis);
    const PixelRays rays(vp, 160, 120);
    size_t covered = 0, checked = 0;
    for (int y = 0; y < 120; ++y)
        for (int x = 0; x < 160; ++x) {
            glm::vec3 o, d;
            rays.pixel_ray(x, y, o, d);
            const double t = -double(o.z) / double(d.z);  // plane z = 0
            const double hx = o.x + t * d.x, hy = o.y + t * d.y;
            const double margin = 0.8 - std::max(std::abs(hx), std::abs(hy));
            const size_t p = size_t(y) * 160 + size_t(x);
            if (std::abs(margin) < 1e-5) continue;  // exactly on the outline: either answer
            ++checked;
            if (margin > 0) {
                ++covered;
                ASSERT_NE(vis.triangle[p], kNoTriangle) << x << "," << y;
                const glm::vec3 hit(float(hx), float(hy), 0.0f);
                EXPECT_NEAR(vis.depth[p], rays.window_depth(hit), 1e-6) << x << "," << y;
            } else {
                ASSERT_EQ(vis.triangle[p], kNoTriangle) << x << "," << y;
                EXPECT_EQ(vis.depth[p], 1.0f);
            }
        }
    EXPECT_GT(covered, 3000u);
    EXPECT_GT(checked, 160u * 120u - 20u);
}

// Nearest hit by a double-precision Moller-Trumbore test over every triangle; also reports
// how close the ray passes to another triangle's hit (ties are an exact-edge matter).
struct ReferenceHit {
    uint32_t triangle = kNoTriangle;
    double t = std::numeric_limits<double>::infinity();
    double edge = std::numeric_limits<double>::infinity();  // smallest barycentric of the hit
};

ReferenceHit reference_hit(const Mesh& mesh, const glm::vec3& o, const glm::vec3& d) {
    ReferenceHit best;
    const glm::dvec3 origin(o), direction(d);
    for (uint32_t t = 0; t < mesh.triangle_count(); ++t) {
        const glm::dvec3 a(mesh.positions[mesh.indices[3 * t]]);
        const glm::dvec3 e1 = glm::dvec3(mesh.positions[mesh.indices[3 * t + 1]]) - a;
        const glm::dvec3 e2 = glm::dvec3(mesh.positions[mesh.indices[3 * t + 2]]) - a;
        const glm::dvec3 p = glm::cross(direction, e2);
        const double det = glm::dot(e1, p);
        if (det == 0.0) continue;
        const glm::dvec3 s = origin - a;
        const double u = glm::dot(s, p) / det;
        const glm::dvec3 q = glm::cross(s, e1);
        const double v = glm::dot(direction, q) / det;
        const double dist = glm::dot(e2, q) / det;
        if (u < 0 || v < 0 || u + v > 1 || dist < 0 || dist > 1) continue;
        if (dist < best.t) best = {t, dist, std::min({u, v, 1 - u - v})};
    }
    return best;
}

TEST(EmbreeRayCast, SphereGridMatchesBruteForceReferenceExceptAtEdges) {
    const workloads::SphereGridScene grid = workloads::make_sphere_grid(2000, 4.0f / 3.0f);
    const RayScene scene(default_ray_device(), grid.mesh);
    const glm::mat4 vp = grid.camera.view_projection();
    const int w = 96, h = 72;
    VisibilityBuffer vis;
    cast_primary_rays(scene, vp, w, h, vis);
    const PixelRays rays(vp, w, h);
    size_t differ = 0, covered = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            glm::vec3 o, d;
            rays.pixel_ray(x, y, o, d);
            const ReferenceHit ref = reference_hit(grid.mesh, o, d);
            const size_t p = size_t(y) * w + size_t(x);
            covered += ref.triangle != kNoTriangle;
            if (vis.triangle[p] == ref.triangle) {
                if (ref.triangle != kNoTriangle) {
                    EXPECT_NEAR(vis.depth[p], rays.window_depth(o + float(ref.t) * d), 1e-6);
                }
                continue;
            }
            ++differ;
            // A different answer is allowed only on (or within float error of) an edge.
            EXPECT_LT(ref.edge, 1e-4) << "pixel " << x << "," << y;
        }
    EXPECT_GT(covered, size_t(w * h) / 3);
    EXPECT_LE(differ, size_t(w * h) / 200);
}

TEST(EmbreeRayCast, PacketWidthsAndThreadCountsGiveIdenticalBuffers) {
    const workloads::SphereGridScene grid = workloads::make_sphere_grid(20000);
    const RayScene scene(default_ray_device(), grid.mesh);
    const glm::mat4 vp = grid.camera.view_projection();
    VisibilityBuffer single, x8, x16, one_thread;
    cast_primary_rays(scene, vp, 203, 117, single, RayPacket::single);
    cast_primary_rays(scene, vp, 203, 117, x8, RayPacket::x8);
    cast_primary_rays(scene, vp, 203, 117, x16, RayPacket::x16);
    {
        const tbb::global_control cap(tbb::global_control::max_allowed_parallelism, 1);
        cast_primary_rays(scene, vp, 203, 117, one_thread, RayPacket::x16);
    }
    EXPECT_EQ(single.triangle, x8.triangle);
    EXPECT_EQ(single.triangle, x16.triangle);
    EXPECT_EQ(single.depth, x16.depth);
    EXPECT_EQ(x16.triangle, one_thread.triangle);
    EXPECT_EQ(x16.depth, one_thread.depth);
}

TEST(EmbreeRayCast, BrokenTrianglesAreCountedAndTheFrameStillRenders) {
    Mesh mesh = quad_mesh(0.8f);
    const float nan = std::numeric_limits<float>::quiet_NaN();
    mesh.positions.push_back({nan, 0.0f, 0.0f});                    // vertex 4: NaN
    mesh.positions.push_back({std::numeric_limits<float>::infinity(), 0.0f, 0.0f});
    mesh.indices.insert(mesh.indices.end(), {0, 4, 2,               // NaN vertex
                                             5, 1, 2,               // infinite vertex
                                             0, 1, 99,              // index out of range
                                             0, 0, 2});             // zero area
    reserve_ray_padding(mesh);
    const RayScene scene(default_ray_device(), mesh);
    EXPECT_EQ(scene.defects().nonfinite, 2u);
    EXPECT_EQ(scene.defects().bad_index, 1u);
    EXPECT_EQ(scene.defects().degenerate, 1u);
    VisibilityBuffer vis;
    cast_primary_rays(scene, front_camera(1.0f).view_projection(), 64, 64, vis);
    const size_t centre = 32 * 64 + 32;
    EXPECT_TRUE(vis.triangle[centre] == 0 || vis.triangle[centre] == 1);
    for (uint32_t id : vis.triangle) EXPECT_TRUE(id == kNoTriangle || id < 2) << id;
}

TEST(EmbreeRayCast, RefitAndRebuildFollowTheAnimatedMesh) {
    workloads::SphereGridScene grid = workloads::make_sphere_grid(5000);
    RayScene refit(default_ray_device(), grid.mesh, BvhUpdate::refit);
    RayScene rebuild(default_ray_device(), grid.mesh, BvhUpdate::rebuild);
    VisibilityBuffer before;
    const glm::mat4 vp = grid.camera.view_projection();
    cast_primary_rays(refit, vp, 160, 90, before);
    workloads::ripple_spheres(grid, 1.0f);
    refit.update();
    rebuild.update();
    const RayScene fresh(default_ray_device(), grid.mesh);
    VisibilityBuffer a, b, c;
    cast_primary_rays(refit, vp, 160, 90, a);
    cast_primary_rays(rebuild, vp, 160, 90, b);
    cast_primary_rays(fresh, vp, 160, 90, c);
    EXPECT_NE(before.triangle, c.triangle);  // the ripple changed the picture
    EXPECT_EQ(a.triangle, c.triangle);
    EXPECT_EQ(b.triangle, c.triangle);
}

TEST(EmbreeDevice, ErrorsBecomeTesseraErrors) {
    const RayDevice device;
    RTCScene scene = rtcNewScene(device.handle());
    // REFIT is a geometry quality only: Embree reports the misuse through the callback.
    rtcSetSceneBuildQuality(scene, RTC_BUILD_QUALITY_REFIT);
    try {
        device.check("set quality");
        ADD_FAILURE() << "no error reported";
    } catch (const Error& error) {
        EXPECT_EQ(std::string(error.what()).rfind("embree: set quality: ", 0), 0u) << error.what();
    }
    rtcReleaseScene(scene);
    EXPECT_NO_THROW(device.check("after the error was reported"));
}

TEST(EmbreeDevice, BuildsRunOnTheSharedOneTbbPool) {
    EXPECT_TRUE(default_ray_device().shares_tbb());
}

TEST(EmbreeDevice, FlushDenormalsSetsAndRestoresTheThreadsMode) {
    const bool before = denormals_flushed();
    {
        const FlushDenormals flush;
        EXPECT_TRUE(denormals_flushed());
        volatile float tiny = 1e-39f;  // a denormal: read as zero under DAZ
        EXPECT_EQ(tiny * 1.0f, 0.0f);
    }
    EXPECT_EQ(denormals_flushed(), before);
}

TEST(EmbreeScene, UnpaddedPositionsAreCopiedNotShared) {
    Mesh mesh;
    mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    mesh.positions.shrink_to_fit();
    mesh.indices = {0, 1, 2};
    if (mesh.positions.capacity() != mesh.positions.size()) GTEST_SKIP() << "no exact capacity";
    const RayScene scene(default_ray_device(), mesh);
    EXPECT_FALSE(scene.shares_vertices());
    Mesh bad = mesh;
    bad.indices.push_back(0);
    EXPECT_THROW(RayScene(default_ray_device(), bad), std::invalid_argument);
}

}  // namespace
}  // namespace tessera::embree
