// Coverage of the tile rasterizer against the scalar reference, pixel for pixel, and the
// D3D11.3 fill-rule properties (top-left rule, watertight shared edges).
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include "raster/rasterizer.h"
#include "raster/reference_rasterizer.h"
#include "raster/test_meshes.h"

namespace tessera {
namespace {

using test_meshes::WindowMesh;

const glm::mat4 kIdentity(1.0f);

// Renders `mesh` with both rasterizers and expects identical ids and depths.
void expect_same_as_reference(const Mesh& mesh, const glm::mat4& vp, int w, int h,
                              RasterOptions options = {}) {
    VisibilityBuffer fast, reference;
    Rasterizer rasterizer;
    rasterizer.render(mesh, vp, Viewport(w, h), options, fast);
    reference_rasterize(mesh, vp, Viewport(w, h), options, reference);
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
    Rasterizer rasterizer;
    VisibilityBuffer vis;
    for (size_t t = 0; t < mesh.triangle_count(); ++t) {
        Mesh one = mesh;
        one.indices.assign(mesh.indices.begin() + 3 * t, mesh.indices.begin() + 3 * t + 3);
        rasterizer.render(one, kIdentity, Viewport(w, h), {}, vis);
        for (size_t i = 0; i < count.size(); ++i) count[i] += vis.triangle[i] != kNoTriangle;
    }
    return count;
}

TEST(RasterCoverage, RandomSmallTrianglesMatchReference) {
    const int w = 320, h = 200;
    expect_same_as_reference(test_meshes::to_world(test_meshes::random_triangles(1, 3000, w, h, 12.0f), kIdentity, w, h),
                             kIdentity, w, h);
}

TEST(RasterCoverage, RandomLargeTrianglesMatchReference) {
    const int w = 301, h = 217;  // odd sizes: partial tiles and stamps at the borders
    expect_same_as_reference(
        test_meshes::to_world(test_meshes::random_triangles(2, 300, w, h, 400.0f, 100.0f), kIdentity, w, h),
        kIdentity, w, h);
}

TEST(RasterCoverage, BackAndFrontCullingMatchReference) {
    const int w = 160, h = 120;
    const Mesh mesh = test_meshes::to_world(test_meshes::random_triangles(3, 500, w, h, 40.0f), kIdentity, w, h);
    for (CullMode cull : {CullMode::back, CullMode::front}) {
        RasterOptions options;
        options.cull = cull;
        expect_same_as_reference(mesh, kIdentity, w, h, options);
    }
}

// D3D11.3 rasterization rules: a 5x5-pixel square split along its diagonal gives 15 pixels to
// one triangle and 10 to the other.
TEST(RasterCoverage, D3DDiagonalSplitGives15And10) {
    const int w = 16, h = 16;
    WindowMesh square;
    square.positions = {{2, 2, 0.5f}, {7, 2, 0.5f}, {7, 7, 0.5f}, {2, 7, 0.5f}};
    square.indices = {0, 1, 2, 0, 2, 3};
    Rasterizer rasterizer;
    VisibilityBuffer vis;
    rasterizer.render(test_meshes::to_world(square, kIdentity, w, h), kIdentity, Viewport(w, h), {}, vis);
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
    WindowMesh square;
    square.positions = {{2.5f, 2.5f, 0.5f}, {6.5f, 2.5f, 0.5f}, {6.5f, 6.5f, 0.5f}, {2.5f, 6.5f, 0.5f}};
    square.indices = {0, 1, 2, 0, 2, 3};
    Rasterizer rasterizer;
    VisibilityBuffer vis;
    rasterizer.render(test_meshes::to_world(square, kIdentity, w, h), kIdentity, Viewport(w, h), {}, vis);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            EXPECT_EQ(vis.triangle[size_t(y) * w + x] != kNoTriangle, x >= 2 && x < 6 && y >= 2 && y < 6)
                << "pixel " << x << "," << y;
}

TEST(RasterCoverage, JitteredGridIsWatertight) {
    const int w = 96, h = 80;
    const Mesh mesh = test_meshes::to_world(test_meshes::grid(4, 9, 7, 0.0f, 0.0f, float(w), float(h), 0.4f),
                                            kIdentity, w, h);
    const std::vector<int> count = coverage_count(mesh, w, h);
    for (size_t i = 0; i < count.size(); ++i) ASSERT_EQ(count[i], 1) << "pixel " << i % w << "," << i / w;
}

TEST(RasterCoverage, FanAroundPixelCentreIsWatertight) {
    const int w = 64, h = 64;
    const Mesh mesh = test_meshes::to_world(test_meshes::fan({32.5f, 32.5f}, 20.0f, 37), kIdentity, w, h);
    const std::vector<int> count = coverage_count(mesh, w, h);
    for (size_t i = 0; i < count.size(); ++i) ASSERT_LE(count[i], 1) << "pixel " << i % w << "," << i / w;
    EXPECT_EQ(count[32 * w + 32], 1);  // the shared centre vertex's pixel belongs to exactly one
}

}  // namespace
}  // namespace tessera
