// The ray-cast renderer against the rasterizer on identical work: the same mesh, camera and
// pixel centres must give the same triangle ids, except where a pixel centre lies on an edge
// (within the rasterizer's 1/256-pixel snapping of the ray's exact answer), and the same
// window depths (the rays' exactly, the rasterizer's within its snapping error).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "raster/core/pixel_rays.h"
#include "raster/embree/ray_cast.h"
#include "raster/embree/scene.h"
#include "raster/pipeline/rasterizer.h"
#include "raster/workloads/sphere_grid.h"
#include "raster/workloads/test_meshes.h"

namespace tessera::embree {
namespace {

// Distance in pixels from the centre of pixel (x, y) to the nearest edge of `triangle`
// projected through `vp` (infinite when a vertex is behind the eye: not an edge case here).
double edge_distance(const Mesh& mesh, uint32_t triangle, const glm::mat4& vp, int w, int h,
                     int x, int y) {
    glm::dvec2 v[3];
    for (int i = 0; i < 3; ++i) {
        const glm::dvec4 c = glm::dmat4(vp) *
                             glm::dvec4(glm::dvec3(mesh.positions[mesh.indices[3 * triangle + i]]), 1.0);
        if (c.w <= 0) return INFINITY;
        v[i] = {(c.x / c.w + 1) * 0.5 * w, (1 - c.y / c.w) * 0.5 * h};
    }
    const glm::dvec2 p(x + 0.5, y + 0.5);
    double nearest = INFINITY;
    for (int i = 0; i < 3; ++i) {
        const glm::dvec2 a = v[i], b = v[(i + 1) % 3];
        const glm::dvec2 ab = b - a;
        const double t = std::clamp(glm::dot(p - a, ab) / glm::dot(ab, ab), 0.0, 1.0);
        nearest = std::min(nearest, glm::length(p - (a + t * ab)));
    }
    return nearest;
}

struct Comparison {
    size_t covered = 0, differ = 0, edge_ties = 0, depth_ties = 0, unexplained = 0;
    size_t depth_beyond_snapping = 0;
};

// The exact window depth of `triangle`'s plane at the centre of (x, y), and how far the
// rasterizer's depth may stray from it: it snaps vertices to 1/256 pixel (fixed_point.h),
// which moves its depth plane Z = aX + bY + c by up to (|a| + |b|) / 256 per vertex moved.
struct ExactDepth {
    double depth, tolerance;
};

ExactDepth exact_depth(const Mesh& mesh, uint32_t triangle, const PixelRays& rays, int x, int y) {
    const auto plane = rays.depth_plane(mesh.positions[mesh.indices[3 * triangle]],
                                        mesh.positions[mesh.indices[3 * triangle + 1]],
                                        mesh.positions[mesh.indices[3 * triangle + 2]]);
    return {plane.per_x * (x + 0.5) + plane.per_y * (y + 0.5) + plane.at_zero,
            (std::abs(plane.per_x) + std::abs(plane.per_y)) * 3.0 / 256.0 + 2e-6};
}

// Renders `mesh` both ways and classifies every pixel where the triangle ids differ: an edge
// tie (the centre within snapping error of an edge of one answer), a depth tie (both
// triangles cover the centre at depths closer than the snapping error: intersecting
// triangles), or unexplained (a test failure). Where the ids agree, the depths must agree
// within the snapping error.
Comparison compare(const Mesh& mesh, const glm::mat4& vp, int w, int h, bool allow_depth_ties) {
    VisibilityBuffer raster, rays;
    pipeline::Rasterizer rasterizer;
    rasterizer.render(mesh, vp, pipeline::Viewport(w, h), pipeline::RasterOptions{}, raster);
    const RayScene scene(default_ray_device(), mesh);
    cast_primary_rays(scene, vp, w, h, rays);
    const PixelRays pixel_rays(vp, w, h);
    Comparison result;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const size_t p = size_t(y) * w + size_t(x);
            const uint32_t a = raster.triangle[p], b = rays.triangle[p];
            result.covered += a != kNoTriangle;
            if (a == b) {
                if (a == kNoTriangle) continue;
                const ExactDepth exact = exact_depth(mesh, a, pixel_rays, x, y);
                EXPECT_NEAR(rays.depth[p], exact.depth, 1e-6) << "pixel " << x << "," << y;
                result.depth_beyond_snapping +=
                    std::abs(raster.depth[p] - exact.depth) > exact.tolerance;
                continue;
            }
            ++result.differ;
            const double near_a = a == kNoTriangle ? INFINITY : edge_distance(mesh, a, vp, w, h, x, y);
            const double near_b = b == kNoTriangle ? INFINITY : edge_distance(mesh, b, vp, w, h, x, y);
            if (std::min(near_a, near_b) <= 1.0 / 128) {
                ++result.edge_ties;
                continue;
            }
            if (allow_depth_ties && a != kNoTriangle && b != kNoTriangle) {
                const ExactDepth za = exact_depth(mesh, a, pixel_rays, x, y);
                const ExactDepth zb = exact_depth(mesh, b, pixel_rays, x, y);
                if (std::abs(za.depth - zb.depth) <= za.tolerance + zb.tolerance) {
                    ++result.depth_ties;
                    continue;
                }
            }
            ++result.unexplained;
            ADD_FAILURE() << "pixel " << x << "," << y << ": raster says triangle " << a
                          << " (depth " << raster.depth[p] << "), rays say " << b << " (depth "
                          << rays.depth[p] << "); nearest edges " << near_a << " / " << near_b
                          << " px away";
        }
    return result;
}

TEST(EmbreeVersusRaster, SphereGridAgreesExceptExactEdges) {
    const workloads::SphereGridScene grid = workloads::make_sphere_grid(30000, 4.0f / 3.0f);
    const Comparison c = compare(grid.mesh, grid.camera.view_projection(), 400, 300, false);
    EXPECT_GT(c.covered, 40000u);
    EXPECT_EQ(c.unexplained, 0u);
    EXPECT_LT(c.differ, c.covered / 200);  // edges are rare
    EXPECT_EQ(c.depth_beyond_snapping, 0u);
}

// Multisampled: one ray per sample position, the rasterizer's coverage per sample; they see
// the same triangle at every sample except near edges (the rasterizer snaps vertices).
TEST(EmbreeVersusRaster, SphereGridAgreesSampleForSample) {
    const workloads::SphereGridScene grid = workloads::make_sphere_grid(20000, 4.0f / 3.0f);
    const int w = 200, h = 150, samples = 4;
    const glm::mat4 vp = grid.camera.view_projection();
    VisibilityBuffer raster, rays;
    pipeline::RasterOptions options;
    options.samples = samples;
    options.keep_samples = true;
    pipeline::Rasterizer rasterizer;
    rasterizer.render(grid.mesh, vp, pipeline::Viewport(w, h), options, raster);
    const RayScene scene(default_ray_device(), grid.mesh);
    cast_primary_rays(scene, vp, w, h, rays, RayPacket::x16, {}, samples);
    ASSERT_EQ(rays.sample_triangle.size(), size_t(w) * h * samples);
    size_t covered = 0, differ = 0, depth_far = 0;
    for (size_t i = 0; i < rays.sample_triangle.size(); ++i) {
        covered += raster.sample_triangle[i] != kNoTriangle;
        differ += raster.sample_triangle[i] != rays.sample_triangle[i];
        if (raster.sample_triangle[i] == rays.sample_triangle[i] && rays.sample_triangle[i] != kNoTriangle)
            depth_far += std::abs(raster.sample_depth[i] - rays.sample_depth[i]) > 1e-4f;
    }
    EXPECT_GT(covered, size_t(w) * h * samples / 4);
    EXPECT_LT(differ, covered / 200);  // edges are rare
    EXPECT_EQ(depth_far, 0u);
    // The main surface of a pixel agrees as often.
    size_t pixel_differ = 0;
    for (size_t p = 0; p < raster.triangle.size(); ++p) pixel_differ += raster.triangle[p] != rays.triangle[p];
    EXPECT_LT(pixel_differ, raster.triangle.size() / 100);
}

TEST(EmbreeVersusRaster, RandomTrianglesThroughAPerspectiveCameraAgree) {
    Camera camera;
    camera.eye = {0.5f, 0.3f, 4.0f};
    camera.aspect = 1.5f;
    const glm::mat4 vp = camera.view_projection();
    // Window-space triangles with random depths, mapped back to world space.
    const Mesh mesh = workloads::to_world(workloads::random_triangles(7, 400, 300, 200, 40.0f),
                                            vp, 300, 200);
    Mesh padded = mesh;
    reserve_ray_padding(padded);
    // Random triangles intersect one another, so depth ties are expected too.
    const Comparison c = compare(padded, vp, 300, 200, true);
    EXPECT_GT(c.covered, 20000u);
    EXPECT_EQ(c.unexplained, 0u);
    EXPECT_EQ(c.depth_beyond_snapping, 0u);
}

TEST(EmbreeVersusRaster, BackgroundAndNearPlaneMatch) {
    // A quad crossing the near plane: the rasterizer clips it, the rays start on the near
    // plane, so both drop the same part.
    Mesh mesh;
    mesh.positions = {{-1, -1, 2.95f}, {1, -1, 2.95f}, {1, 1, 0}, {-1, 1, 0}};
    mesh.indices = {0, 1, 2, 0, 2, 3};
    reserve_ray_padding(mesh);
    Camera camera;
    camera.aspect = 1.0f;
    const Comparison c = compare(mesh, camera.view_projection(), 128, 128, false);
    EXPECT_GT(c.covered, 1000u);
    EXPECT_EQ(c.unexplained, 0u);
}

}  // namespace
}  // namespace tessera::embree
