// Coverage of the tile rasterizer against the scalar reference, pixel for pixel, and the
// D3D11.3 fill-rule properties (top-left rule, watertight shared edges).
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>

#include "raster/pipeline/rasterizer.h"
#include "raster/pipeline/reference_rasterizer.h"
#include "procedural/hash.h"
#include "raster/core/camera.h"
#include "raster/workloads/test_meshes.h"

namespace tessera {
namespace {

using workloads::WindowMesh;

const glm::mat4 kIdentity(1.0f);

// Renders `mesh` with both rasterizers and expects identical ids and depths.
void expect_same_as_reference(const Mesh& mesh, const glm::mat4& vp, int w, int h,
                              pipeline::RasterOptions options = {}) {
    VisibilityBuffer fast, reference;
    pipeline::Rasterizer rasterizer;
    rasterizer.render(mesh, vp, pipeline::Viewport(w, h), options, fast);
    pipeline::reference_rasterize(mesh, vp, pipeline::Viewport(w, h), options, reference);
    size_t id_mismatch = 0, depth_mismatch = 0, covered = 0;
    for (size_t i = 0; i < fast.triangle.size(); ++i) {
        id_mismatch += fast.triangle[i] != reference.triangle[i];
        depth_mismatch += fast.depth[i] != reference.depth[i];
        covered += reference.triangle[i] != kNoTriangle;
        if (id_mismatch == 1 && fast.triangle[i] != reference.triangle[i])
            ADD_FAILURE() << "first mismatch at pixel (" << i % w << ", " << i / w << "): fast "
                          << fast.triangle[i] << " reference " << reference.triangle[i];
    }
    EXPECT_EQ(id_mismatch, 0u);
    EXPECT_EQ(depth_mismatch, 0u);
    EXPECT_GT(covered, 0u) << "the scene should cover something";
}

// Number of triangles of `mesh` covering each pixel (depth test off: every triangle is drawn
// alone, so overlaps are counted).
std::vector<int> coverage_count(const Mesh& mesh, int w, int h) {
    std::vector<int> count(size_t(w) * h, 0);
    pipeline::Rasterizer rasterizer;
    VisibilityBuffer vis;
    for (size_t t = 0; t < mesh.triangle_count(); ++t) {
        Mesh one = mesh;
        one.indices.assign(mesh.indices.begin() + 3 * t, mesh.indices.begin() + 3 * t + 3);
        rasterizer.render(one, kIdentity, pipeline::Viewport(w, h), {}, vis);
        for (size_t i = 0; i < count.size(); ++i) count[i] += vis.triangle[i] != kNoTriangle;
    }
    return count;
}

TEST(RasterCoverage, RandomSmallTrianglesMatchReference) {
    const int w = 320, h = 200;
    expect_same_as_reference(workloads::to_world(workloads::random_triangles(1, 3000, w, h, 12.0f), kIdentity, w, h),
                             kIdentity, w, h);
}

TEST(RasterCoverage, RandomLargeTrianglesMatchReference) {
    const int w = 301, h = 217;  // odd sizes: partial tiles and stamps at the borders
    expect_same_as_reference(
        workloads::to_world(workloads::random_triangles(2, 300, w, h, 400.0f, 100.0f), kIdentity, w, h),
        kIdentity, w, h);
}

// Vertices on pixel centres, pixel corners and half-way points: exact ties on edges, the
// case the top-left rule decides.
TEST(RasterCoverage, TrianglesOnPixelGridMatchReference) {
    const int w = 200, h = 150;
    workloads::WindowMesh m = workloads::random_triangles(5, 4000, w, h, 24.0f);
    for (glm::vec3& p : m.positions) {
        p.x = std::round(p.x * 2.0f) * 0.5f;
        p.y = std::round(p.y * 2.0f) * 0.5f;
    }
    expect_same_as_reference(workloads::to_world(m, kIdentity, w, h), kIdentity, w, h);
}

// Slivers (one edge much shorter than the others, or nearly collinear vertices), zero-area
// and repeated-vertex triangles.
TEST(RasterCoverage, SliversAndDegeneratesMatchReference) {
    const int w = 256, h = 160;
    workloads::WindowMesh m = workloads::random_triangles(6, 2000, w, h, 200.0f, 20.0f);
    for (size_t t = 0; t < m.indices.size() / 3; ++t) {
        glm::vec3* p = &m.positions[3 * t];
        switch (t % 4) {
            case 0: p[2] = glm::mix(p[0], p[1], 0.37f) + glm::vec3(0.01f, -0.02f, 0.0f); break;  // sliver
            case 1: p[2] = glm::mix(p[0], p[1], 0.5f); break;                                   // collinear
            case 2: p[1] = p[0]; break;                                                          // repeated
            default: p[1] = p[0] + glm::vec3(0.004f, 300.0f, 0.0f); break;                      // needle
        }
    }
    expect_same_as_reference(workloads::to_world(m, kIdentity, w, h), kIdentity, w, h);
}

// Coordinates far beyond the viewport (guard band clipping) and beyond float-to-fixed range.
TEST(RasterCoverage, HugeCoordinatesMatchReference) {
    const int w = 128, h = 96;
    workloads::WindowMesh m = workloads::random_triangles(8, 600, w, h, 1e5f, 2e4f);
    workloads::WindowMesh huge = workloads::random_triangles(9, 200, w, h, 1e9f, 1e8f);
    for (uint32_t& i : huge.indices) i += uint32_t(m.positions.size());
    m.positions.insert(m.positions.end(), huge.positions.begin(), huge.positions.end());
    m.indices.insert(m.indices.end(), huge.indices.begin(), huge.indices.end());
    expect_same_as_reference(workloads::to_world(m, kIdentity, w, h), kIdentity, w, h);
}

// A perspective camera with triangles crossing the near plane and w = 0 (partly behind the
// eye): clipped in homogeneous coordinates, not dropped.
TEST(RasterCoverage, NearPlaneCrossingMatchesReference) {
    const int w = 160, h = 120;
    Camera camera;
    camera.eye = {0.0f, 0.0f, 0.0f};
    camera.lookat = {0.0f, 0.0f, -1.0f};
    camera.aspect = float(w) / float(h);
    camera.near = 0.5f;
    camera.far = 20.0f;
    Mesh mesh;
    procedural::SplitMix64 rng(11);
    auto r = [&](float lo, float hi) { return lo + (hi - lo) * rng.next_float(); };
    for (int t = 0; t < 400; ++t) {
        for (int k = 0; k < 3; ++k) {
            mesh.indices.push_back(uint32_t(mesh.positions.size()));
            // z from behind the eye (+4) to beyond the far plane (-25)
            mesh.positions.push_back({r(-6.0f, 6.0f), r(-5.0f, 5.0f), r(-25.0f, 4.0f)});
        }
    }
    pipeline::RasterStats stats;
    VisibilityBuffer vis;
    pipeline::Rasterizer rasterizer;
    rasterizer.render(mesh, camera.view_projection(), pipeline::Viewport(w, h), {}, vis, {}, nullptr, &stats);
    EXPECT_GT(stats.clipped, 100u);
    expect_same_as_reference(mesh, camera.view_projection(), w, h);
}

TEST(RasterCoverage, BackAndFrontCullingMatchReference) {
    const int w = 160, h = 120;
    const Mesh mesh = workloads::to_world(workloads::random_triangles(3, 500, w, h, 40.0f), kIdentity, w, h);
    for (pipeline::CullMode cull : {pipeline::CullMode::back, pipeline::CullMode::front}) {
        pipeline::RasterOptions options;
        options.cull = cull;
        expect_same_as_reference(mesh, kIdentity, w, h, options);
    }
}

// D3D11.3 rasterization rules: a 5x5-pixel square split along its diagonal gives 15 pixels to
// one triangle and 10 to the other.
TEST(RasterCoverage, D3DDiagonalSplitGives15And10) {
    const int w = 16, h = 16;
    workloads::WindowMesh square;
    square.positions = {{2, 2, 0.5f}, {7, 2, 0.5f}, {7, 7, 0.5f}, {2, 7, 0.5f}};
    square.indices = {0, 1, 2, 0, 2, 3};
    pipeline::Rasterizer rasterizer;
    VisibilityBuffer vis;
    rasterizer.render(workloads::to_world(square, kIdentity, w, h), kIdentity, pipeline::Viewport(w, h), {}, vis);
    int count[2] = {0, 0};
    for (uint32_t id : vis.triangle)
        if (id != kNoTriangle) ++count[id];
    EXPECT_EQ(count[0] + count[1], 25);
    EXPECT_EQ(std::max(count[0], count[1]), 15);
    EXPECT_EQ(std::min(count[0], count[1]), 10);
}

TEST(RasterCoverage, TopLeftRuleOnPixelCentres) {
    // A 4x4 square whose edges pass exactly through pixel centres: the left and top rows of
    // centres are inside, the right and bottom ones are not (16 pixels, not 25).
    const int w = 16, h = 16;
    workloads::WindowMesh square;
    square.positions = {{2.5f, 2.5f, 0.5f}, {6.5f, 2.5f, 0.5f}, {6.5f, 6.5f, 0.5f}, {2.5f, 6.5f, 0.5f}};
    square.indices = {0, 1, 2, 0, 2, 3};
    pipeline::Rasterizer rasterizer;
    VisibilityBuffer vis;
    rasterizer.render(workloads::to_world(square, kIdentity, w, h), kIdentity, pipeline::Viewport(w, h), {}, vis);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            EXPECT_EQ(vis.triangle[size_t(y) * w + x] != kNoTriangle, x >= 2 && x < 6 && y >= 2 && y < 6)
                << "pixel " << x << "," << y;
}

TEST(RasterCoverage, JitteredGridIsWatertight) {
    const int w = 96, h = 80;
    const Mesh mesh = workloads::to_world(workloads::grid(4, 9, 7, 0.0f, 0.0f, float(w), float(h), 0.4f),
                                            kIdentity, w, h);
    const std::vector<int> count = coverage_count(mesh, w, h);
    for (size_t i = 0; i < count.size(); ++i) ASSERT_EQ(count[i], 1) << "pixel " << i % w << "," << i / w;
}

TEST(RasterCoverage, FanAroundPixelCentreIsWatertight) {
    const int w = 64, h = 64;
    const Mesh mesh = workloads::to_world(workloads::fan({32.5f, 32.5f}, 20.0f, 37), kIdentity, w, h);
    const std::vector<int> count = coverage_count(mesh, w, h);
    for (size_t i = 0; i < count.size(); ++i) ASSERT_LE(count[i], 1) << "pixel " << i % w << "," << i / w;
    EXPECT_EQ(count[32 * w + 32], 1);  // the shared centre vertex's pixel belongs to exactly one
}

}  // namespace
}  // namespace tessera
