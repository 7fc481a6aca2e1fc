// Multisampling in the tile rasterizer: coverage and depth per sample against the scalar
// reference, sample for sample (the D3D11.3 fill rule at the standard sample positions),
// watertight shared edges per sample, and the resolve of the passes' colour per surface.
#include <gtest/gtest.h>

#include <tbb/global_control.h>

#include <cmath>
#include <set>

#include "raster/core/coverage_layers.h"
#include "raster/pipeline/rasterizer.h"
#include "raster/pipeline/reference_rasterizer.h"
#include "raster/pipeline/sample_pattern.h"
#include "raster/workloads/test_meshes.h"

namespace tessera {
namespace {

const glm::mat4 kIdentity(1.0f);

pipeline::RasterOptions multisampled(int samples) {
    pipeline::RasterOptions options;
    options.samples = samples;
    options.keep_samples = true;
    return options;
}

// Renders `mesh` with both rasterizers and expects identical ids and depths at every sample
// and the same main surface per pixel.
void expect_samples_match_reference(const Mesh& mesh, int w, int h, int samples, int tile_size = 128) {
    pipeline::RasterOptions options = multisampled(samples);
    options.tile_size = tile_size;
    VisibilityBuffer fast, reference;
    pipeline::Rasterizer rasterizer;
    rasterizer.render(mesh, kIdentity, pipeline::Viewport(w, h), options, fast);
    pipeline::reference_rasterize(mesh, kIdentity, pipeline::Viewport(w, h), options, reference);
    ASSERT_EQ(fast.samples, samples);
    ASSERT_EQ(fast.sample_triangle.size(), size_t(w) * h * samples);
    ASSERT_EQ(reference.sample_triangle.size(), fast.sample_triangle.size());
    size_t id_mismatch = 0, depth_mismatch = 0, covered = 0;
    for (size_t i = 0; i < fast.sample_triangle.size(); ++i) {
        if (fast.sample_triangle[i] != reference.sample_triangle[i] && id_mismatch++ == 0)
            ADD_FAILURE() << samples << " samples: first mismatch at pixel (" << i / samples % w << ", "
                          << i / samples / w << ") sample " << i % samples << ": fast " << fast.sample_triangle[i]
                          << " reference " << reference.sample_triangle[i];
        depth_mismatch += fast.sample_depth[i] != reference.sample_depth[i];
        covered += reference.sample_triangle[i] != kNoTriangle;
    }
    EXPECT_EQ(id_mismatch, 0u);
    EXPECT_EQ(depth_mismatch, 0u);
    EXPECT_GT(covered, 0u);
    EXPECT_EQ(fast.triangle, reference.triangle);
    EXPECT_EQ(fast.depth, reference.depth);
}

TEST(RasterMsaa, StandardPatterns) {
    for (int n : {1, 4, 8, 16}) {
        const auto pattern = pipeline::sample_pattern(n);
        ASSERT_EQ(int(pattern.size()), n);
        std::set<std::pair<int, int>> distinct;
        for (const pipeline::SampleOffset& o : pattern) {
            EXPECT_TRUE(o.x >= -8 && o.x <= 7 && o.y >= -8 && o.y <= 7);
            distinct.insert({o.x, o.y});
        }
        EXPECT_EQ(int(distinct.size()), n);
    }
    EXPECT_EQ(pipeline::sample_pattern(4)[0].x, -2);  // D3D: (-2, -6), (6, -2), (-6, 2), (2, 6)
    EXPECT_EQ(pipeline::sample_pattern(4)[0].y, -6);
    for (int bad : {0, 2, 3, 5, 32, -4}) EXPECT_THROW(pipeline::sample_pattern(bad), std::invalid_argument);
}

TEST(RasterMsaa, RandomTrianglesMatchReferencePerSample) {
    const int w = 203, h = 131;  // odd sizes: partial tiles and stamps at the borders
    const Mesh small = workloads::to_world(workloads::random_triangles(21, 1500, w, h, 10.0f), kIdentity, w, h);
    const Mesh large = workloads::to_world(workloads::random_triangles(22, 120, w, h, 300.0f, 60.0f), kIdentity, w, h);
    for (int samples : {4, 8, 16}) {
        expect_samples_match_reference(small, w, h, samples);
        expect_samples_match_reference(large, w, h, samples, 64);
    }
}

// Vertices on the 1/16-pixel grid the sample positions sit on: exact ties on edges at
// samples, which the top-left rule decides.
TEST(RasterMsaa, TrianglesOnSampleGridMatchReference) {
    const int w = 96, h = 72;
    workloads::WindowMesh m = workloads::random_triangles(23, 1500, w, h, 20.0f);
    for (glm::vec3& p : m.positions) {
        p.x = std::round(p.x * 16.0f) / 16.0f;
        p.y = std::round(p.y * 16.0f) / 16.0f;
    }
    const Mesh mesh = workloads::to_world(m, kIdentity, w, h);
    for (int samples : {4, 16}) expect_samples_match_reference(mesh, w, h, samples);
}

// Slivers, needles and coordinates far beyond the viewport (guard band clipping).
TEST(RasterMsaa, SliversAndHugeTrianglesMatchReference) {
    const int w = 128, h = 96;
    workloads::WindowMesh m = workloads::random_triangles(24, 600, w, h, 150.0f, 20.0f);
    for (size_t t = 0; t < m.indices.size() / 3; ++t) {
        glm::vec3* p = &m.positions[3 * t];
        if (t % 3 == 0) p[2] = glm::mix(p[0], p[1], 0.37f) + glm::vec3(0.01f, -0.02f, 0.0f);
        if (t % 3 == 1) p[1] = p[0] + glm::vec3(0.004f, 300.0f, 0.0f);
    }
    workloads::WindowMesh huge = workloads::random_triangles(25, 100, w, h, 1e5f, 2e4f);
    for (uint32_t& i : huge.indices) i += uint32_t(m.positions.size());
    m.positions.insert(m.positions.end(), huge.positions.begin(), huge.positions.end());
    m.indices.insert(m.indices.end(), huge.indices.begin(), huge.indices.end());
    expect_samples_match_reference(workloads::to_world(m, kIdentity, w, h), w, h, 8);
}

// Shared edges: every sample of a jittered grid of triangles is covered by exactly one of
// them (each drawn alone, so that overlaps would be counted), in the reference, whose rule is
// written out directly, and, through the sample-for-sample match, in the tile rasterizer.
TEST(RasterMsaa, SharedEdgesCoverEverySampleOnce) {
    const int w = 48, h = 40, samples = 4;
    const Mesh mesh = workloads::to_world(workloads::grid(26, 6, 5, 0.0f, 0.0f, float(w), float(h), 0.45f),
                                          kIdentity, w, h);
    std::vector<int> fast_count(size_t(w) * h * samples, 0), reference_count(fast_count.size(), 0);
    pipeline::Rasterizer rasterizer;
    VisibilityBuffer fast, reference;
    for (size_t t = 0; t < mesh.triangle_count(); ++t) {
        Mesh one = mesh;
        one.indices.assign(mesh.indices.begin() + 3 * t, mesh.indices.begin() + 3 * t + 3);
        rasterizer.render(one, kIdentity, pipeline::Viewport(w, h), multisampled(samples), fast);
        pipeline::reference_rasterize(one, kIdentity, pipeline::Viewport(w, h), multisampled(samples), reference);
        for (size_t i = 0; i < fast_count.size(); ++i) {
            fast_count[i] += fast.sample_triangle[i] != kNoTriangle;
            reference_count[i] += reference.sample_triangle[i] != kNoTriangle;
        }
    }
    for (size_t i = 0; i < fast_count.size(); ++i) {
        ASSERT_EQ(reference_count[i], 1) << "pixel " << i / samples % w << "," << i / samples / w << " sample " << i % samples;
        ASSERT_EQ(fast_count[i], 1) << "pixel " << i / samples % w << "," << i / samples / w << " sample " << i % samples;
    }
}

// A pass that paints each triangle a flat colour of its own: the resolved colour of a pixel
// is then exactly the mean of its samples' colours (shading once per surface, weighted by the
// samples it covers), and the same for any thread count.
glm::vec4 flat_colour(uint32_t triangle) {
    if (triangle == kNoTriangle) return {0.25f, 0.5f, 1.0f, 1.0f};
    return {float(triangle % 7) / 8.0f, float(triangle % 5) / 4.0f, float(triangle % 3) / 2.0f, 1.0f};
}

TEST(RasterMsaa, PassesResolvePerSurface) {
    const int w = 150, h = 90, samples = 4;
    const Mesh mesh = workloads::to_world(workloads::random_triangles(27, 400, w, h, 25.0f), kIdentity, w, h);
    const pipeline::TilePass paint = [&](const pipeline::TileContext& c) {
        for (int y = c.rect.y0; y < c.rect.y1; ++y)
            for (int x = c.rect.x0; x < c.rect.x1; ++x)
                if (c.active(x, y)) c.colour_at(x, y) = flat_colour(c.triangle_at(x, y));
    };
    pipeline::Rasterizer rasterizer;
    VisibilityBuffer vis;
    std::vector<glm::vec4> colour, one_thread;
    rasterizer.render(mesh, kIdentity, pipeline::Viewport(w, h), multisampled(samples), vis, {&paint, 1}, &colour);
    {
        const tbb::global_control cap(tbb::global_control::max_allowed_parallelism, 1);
        VisibilityBuffer v;
        rasterizer.render(mesh, kIdentity, pipeline::Viewport(w, h), multisampled(samples), v, {&paint, 1}, &one_thread);
    }
    EXPECT_TRUE(colour == one_thread);
    size_t edge_pixels = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            glm::vec4 expected(0.0f);
            std::set<uint32_t> surfaces;
            for (int s = 0; s < samples; ++s) {
                const uint32_t t = vis.sample_triangle[vis.sample_index(x, y, s)];
                expected += flat_colour(t) * 0.25f;
                surfaces.insert(t);
            }
            edge_pixels += surfaces.size() > 1;
            const glm::vec4 got = colour[size_t(y) * w + x];
            ASSERT_NEAR(got.r, expected.r, 1e-6f) << x << "," << y;
            ASSERT_NEAR(got.g, expected.g, 1e-6f) << x << "," << y;
            ASSERT_NEAR(got.b, expected.b, 1e-6f) << x << "," << y;
            ASSERT_EQ(got.a, 1.0f);
        }
    EXPECT_GT(edge_pixels, 500u) << "the scene should have many pixels on edges";
}

TEST(RasterMsaa, CoverageLayersWeighSurfaces) {
    // One pixel: samples show triangle 7, nothing, 7, 3: layer 0 is 7 (two samples), then
    // nothing, then 3, in sample order; partly covering, each is evaluated at its first
    // sample.
    const uint32_t ids[4] = {7, kNoTriangle, 7, 3};
    const float depths[4] = {0.5f, 1.0f, 0.25f, 0.75f};
    CoverageLayers layers;
    const glm::vec2 positions[4] = {{-0.125f, -0.375f}, {0.375f, -0.125f}, {-0.375f, 0.125f}, {0.125f, 0.375f}};
    layers.build(TileRect{3, 4, 4, 5}, 4, positions, [&](int x, int y, int s, uint32_t& t, float& d) {
        EXPECT_EQ(x, 3);
        EXPECT_EQ(y, 4);
        t = ids[s];
        d = depths[s];
    });
    ASSERT_EQ(layers.layers(), 3);
    EXPECT_EQ(layers.covered_pixels(), 1u);
    const uint32_t expect_id[3] = {7, kNoTriangle, 3};
    const float expect_depth[3] = {0.25f, 1.0f, 0.75f};
    const int expect_cover[3] = {2, 1, 1};
    glm::vec4 out(-1.0f);
    for (int j = 0; j < 3; ++j) {
        const Tile t = layers.layer(j, glm::vec4(0.0f), &out, 1);
        EXPECT_EQ(t.triangle_at(3, 4), expect_id[j]);
        EXPECT_EQ(t.depth_at(3, 4), expect_depth[j]);
        EXPECT_EQ(int(t.coverage[0]), expect_cover[j]);
        // Evaluated at each surface's first sample: 0, 1 and 3.
        EXPECT_EQ(t.centroid[0], positions[j == 0 ? 0 : j == 1 ? 1 : 3]);
        t.colour_at(3, 4) = glm::vec4(float(j + 1));
        layers.accumulate();
    }
    EXPECT_EQ(out, glm::vec4(0.5f * 1 + 0.25f * 2 + 0.25f * 3));
}

TEST(RasterMsaa, SparseLayersCoverTheirPixelsAndResolveEveryPixel) {
    // A 37x29 tile at (70, 45) whose 4 samples show one of a few surfaces: mostly one per
    // pixel, with a cluster of mixed pixels (up to four surfaces) in one corner and a few
    // strays. Each layer j > 0 must hold every pixel that has a (j+1)-th surface and stay in
    // their bounding box grown by one pixel; build() and build_planes() must agree; and the
    // resolve must equal the direct average of the samples' colours.
    const TileRect rect{70, 45, 107, 74};
    const int w = rect.width(), h = rect.height(), samples = 4;
    const size_t area = size_t(w) * size_t(h);
    std::vector<uint32_t> ids(area * samples);
    std::vector<float> depths(area * samples);
    uint32_t seed = 12345u;
    const auto next = [&] { return seed = seed * 1664525u + 1013904223u; };
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const size_t p = size_t(y) * size_t(w) + size_t(x);
            const bool mixed = (x > 25 && y > 18) || next() % 97 == 0;
            const uint32_t base = uint32_t(x / 9 + y / 7);
            for (int s = 0; s < samples; ++s) {
                const uint32_t r = next() % 5;
                ids[size_t(s) * area + p] = mixed ? (r == 4 ? kNoTriangle : base + r) : base;
                depths[size_t(s) * area + p] = float(next() % 1000) / 1000.0f;
            }
        }
    const glm::vec2* positions = pipeline::sample_positions(samples);
    const auto colour_of = [](uint32_t t, int x, int y) {
        return t == kNoTriangle ? glm::vec4(0.25f, 0.5f, 0.75f, 1.0f)
                                : glm::vec4(float(t % 7) / 7.0f, float(x) / 128.0f, float(y) / 128.0f, 1.0f);
    };
    std::vector<glm::vec4> resolved[2];
    for (int way = 0; way < 2; ++way) {
        CoverageLayers layers;
        if (way == 0)
            layers.build_planes(rect, samples, positions, ids.data(), depths.data());
        else
            layers.build(rect, samples, positions, [&](int x, int y, int s, uint32_t& t, float& d) {
                const size_t p = size_t(y - rect.y0) * size_t(w) + size_t(x - rect.x0);
                t = ids[size_t(s) * area + p];
                d = depths[size_t(s) * area + p];
            });
        ASSERT_EQ(layers.layers(), 4);
        resolved[way].assign(area, glm::vec4(-1.0f));
        for (int j = 0; j < layers.layers(); ++j) {
            const Tile t = layers.layer(j, glm::vec4(0.0f), resolved[way].data(), size_t(w));
            // Every pixel with a (j+1)-th surface is inside, and the rect is their bounding
            // box grown by one pixel.
            TileRect box{rect.x1, rect.y1, rect.x0, rect.y0};
            for (int y = rect.y0; y < rect.y1; ++y)
                for (int x = rect.x0; x < rect.x1; ++x) {
                    std::set<uint32_t> surfaces;
                    for (int s = 0; s < samples; ++s)
                        surfaces.insert(ids[size_t(s) * area + size_t(y - rect.y0) * size_t(w) + size_t(x - rect.x0)]);
                    if (int(surfaces.size()) <= j) continue;
                    box = {std::min(box.x0, x), std::min(box.y0, y), std::max(box.x1, x + 1), std::max(box.y1, y + 1)};
                    ASSERT_TRUE(x >= t.rect.x0 && x < t.rect.x1 && y >= t.rect.y0 && y < t.rect.y1) << j;
                    ASSERT_GT(int(t.coverage[t.offset(x, y)]), 0) << x << "," << y << " layer " << j;
                }
            if (j > 0) {
                EXPECT_EQ(t.rect.x0, std::max(box.x0 - 1, rect.x0)) << j;
                EXPECT_EQ(t.rect.y0, std::max(box.y0 - 1, rect.y0)) << j;
                EXPECT_EQ(t.rect.x1, std::min(box.x1 + 1, rect.x1)) << j;
                EXPECT_EQ(t.rect.y1, std::min(box.y1 + 1, rect.y1)) << j;
            }
            for (int y = t.rect.y0; y < t.rect.y1; ++y)
                for (int x = t.rect.x0; x < t.rect.x1; ++x)
                    if (t.active(x, y)) t.colour_at(x, y) = colour_of(t.triangle_at(x, y), x, y);
            layers.accumulate();
        }
    }
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const size_t p = size_t(y) * size_t(w) + size_t(x);
            glm::vec4 expected(0.0f);
            for (int s = 0; s < samples; ++s)
                expected += colour_of(ids[size_t(s) * area + p], rect.x0 + x, rect.y0 + y) * 0.25f;
            const glm::vec4 got = resolved[0][p];
            ASSERT_EQ(got, resolved[1][p]) << x << "," << y;
            for (int c = 0; c < 4; ++c) ASSERT_NEAR(got[c], expected[c], 1e-6f) << x << "," << y;
        }
}

TEST(RasterMsaa, BadSampleCountsAreRejected) {
    const int w = 32, h = 32;
    const Mesh mesh = workloads::to_world(workloads::random_triangles(28, 10, w, h, 10.0f), kIdentity, w, h);
    pipeline::Rasterizer rasterizer;
    VisibilityBuffer vis;
    for (int bad : {0, 2, 3, 32}) {
        pipeline::RasterOptions options;
        options.samples = bad;
        EXPECT_THROW(rasterizer.render(mesh, kIdentity, pipeline::Viewport(w, h), options, vis), std::invalid_argument);
    }
    pipeline::RasterOptions depth_only = multisampled(4);
    depth_only.depth_only = true;
    EXPECT_THROW(rasterizer.render(mesh, kIdentity, pipeline::Viewport(w, h), depth_only, vis), std::invalid_argument);
}

}  // namespace
}  // namespace tessera
