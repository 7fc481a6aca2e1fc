// The tile rasterizer (raster/pipeline/tile_raster.h) against a brute-force evaluation of the
// setup's edge functions (int64, every pixel) and depth_offset(): coverage, depth and ids of
// each path (tiny and small triangles stepped in int32 lanes, big ones by 16x16 blocks with
// trivial accept and reject, the depth-only and the depth-tested fragment variants) for
// triangles of every size class, tile sizes 16 .. 256, partial tiles at the viewport's borders
// and tiles at the far corner of the largest viewport; and the tile buffers' layout and flush.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdlib>
#include <tuple>
#include <vector>

#include "pipeline_fixtures.h"
#include "raster/core/visibility.h"
#include "raster/pipeline/tile_raster.h"

namespace tessera::pipeline {
namespace {

using test::Rng;
using test::setup_covers;

constexpr int kTileSizes[] = {16, 32, 64, 128, 256};

// The size classes of traversal: a small triangle whose stamp region is under 32 pixels
// (branch-free), other small triangles (vertex box under 128 pixels), big triangles (blocks),
// and huge ones reaching out to the guard band.
struct Classes {
    int tiny = 0, small = 0, big = 0, huge = 0;
};

std::vector<TriangleSetup> random_setups(Rng& rng, int width, int height, int count, Classes& classes) {
    std::vector<TriangleSetup> setups =
        test::random_setups(rng, Viewport(width, height), count, {2, 6, 14, 40, 63, 150, 400, 16000});
    for (const TriangleSetup& t : setups) {
        const int32_t longest = std::max({std::abs(t.dx[0]), std::abs(t.dx[1]), std::abs(t.dx[2]), std::abs(t.dy[0]),
                                          std::abs(t.dy[1]), std::abs(t.dy[2])});
        if (longest > 2000 * kSubpixels) ++classes.huge;
        else if (!t.small) ++classes.big;
        else if (t.maxx - t.minx < 28 && t.maxy - t.miny < 28) ++classes.tiny;
        else ++classes.small;
    }
    return setups;
}

// Tiles of a width x height viewport cut into size x size tiles.
std::vector<TileRect> tiles(int width, int height, int size) {
    std::vector<TileRect> out;
    for (int y = 0; y < height; y += size)
        for (int x = 0; x < width; x += size) out.push_back({x, y, std::min(x + size, width), std::min(y + size, height)});
    return out;
}

bool meets(const TriangleSetup& t, const TileRect& r) {
    return t.maxx >= r.x0 && t.minx < r.x1 && t.maxy >= r.y0 && t.miny < r.y1;
}

// `t` rasterized alone into cleared buffers: at every pixel of the tile, written exactly where
// the edge functions cover it and its depth offset is LESS than the cleared 0 (the far plane),
// with depth_offset(t, x, y) to the bit and the triangle's id (ids untouched for a depth-only
// render). Outside the
// setup's box nothing may be covered (the setup tests prove it of the edge functions), so
// only untouched pixels are checked there.
void expect_alone(const TriangleSetup& t, const TileRect& r, const TileBuffers& b, bool ids, size_t& covered) {
    for (int y = r.y0; y < r.y1; ++y)
        for (int x = r.x0; x < r.x1; ++x) {
            const bool in_box = x >= t.minx && x <= t.maxx && y >= t.miny && y <= t.maxy;
            const bool in = in_box && setup_covers(t, x, y);
            const float z = in ? depth_offset(t, x, y) : 0.0f;
            const bool written = in && z < 0.0f;
            const size_t i = b.index(x - r.x0, y - r.y0);
            const float depth = written ? z : 0.0f;
            const uint32_t id = written && ids ? t.triangle : kNoTriangle;
            if (std::bit_cast<uint32_t>(b.depth[i]) != std::bit_cast<uint32_t>(depth) || b.triangle[i] != id) {
                FAIL() << "triangle " << t.triangle << (t.small ? " (small)" : " (big)") << " box [" << t.minx
                       << ", " << t.maxx << "] x [" << t.miny << ", " << t.maxy << "], tile at (" << r.x0 << ", "
                       << r.y0 << "), pixel (" << x << ", " << y << "): depth " << b.depth[i] << " id "
                       << b.triangle[i] << ", expected " << depth << " id " << id;
            }
            covered += written;
        }
}

TEST(PipelineTileRaster, EachTriangleAloneMatchesItsEdgeFunctions) {
    const int w = 333, h = 259;  // partial tiles at the right and bottom for every size
    Rng rng(16301);
    Classes classes;
    const std::vector<TriangleSetup> setups = random_setups(rng, w, h, 160, classes);
    size_t covered = 0;
    TileBuffers opaque, depth_only;
    for (int size : kTileSizes) {
        for (const TileRect& r : tiles(w, h, size))
            for (const TriangleSetup& t : setups) {
                if (!meets(t, r)) continue;
                opaque.clear(size);
                depth_only.clear(size);
                rasterize_opaque(t, r, opaque);
                rasterize_depth(t, r, depth_only);
                expect_alone(t, r, opaque, true, covered);
                if (HasFatalFailure()) return;
                expect_alone(t, r, depth_only, false, covered);
                if (HasFatalFailure()) return;
            }
    }
    EXPECT_GT(classes.tiny, 25);
    EXPECT_GT(classes.small, 25);
    EXPECT_GT(classes.big, 25);
    EXPECT_GT(classes.huge, 10);
    EXPECT_GT(covered, 1000000u);
}

// Edges exactly through pixel centres (E = 0: the fill rule decides) at every offset from a
// 16x16 block's and a stamp's corner, vertical, horizontal and diagonal, inside on either
// side: where an edge function is 0 or -1 at a block's or a stamp's extreme pixel, trivial
// accept and reject and the stamp tests are decided by one value. Big and small triangles.
TEST(PipelineTileRaster, EdgesThroughPixelCentresAtEveryBlockOffset) {
    const Viewport viewport(512, 384);
    TileBuffers buffers;
    size_t covered = 0;
    uint32_t id = 0;
    auto centre = [](int x, int y) { return WindowVertex{x * 256 + 128, y * 256 + 128, 0.25f}; };
    for (int length : {150, 60})  // big (blocks) and small (stamps only)
        for (int j = 0; j < 16; ++j) {
            const int c = 192 + j, r = 128 + j, side = length * 9 / 8;
            const WindowVertex triangles[][3] = {
                {centre(c, 100), centre(c, 100 + length), centre(c + side, 100 + length / 2)},  // left edge
                {centre(c, 100), centre(c, 100 + length), centre(c - side, 100 + length / 2)},  // right edge
                {centre(100, r), centre(100 + length, r), centre(100 + length / 2, r + side)},  // top edge
                {centre(100, r), centre(100 + length, r), centre(100 + length / 2, r - side)},  // bottom edge
                {centre(c, r), centre(c + length, r + length), centre(c, r + length)},          // diagonals
                {centre(c, r), centre(c + length, r + length), centre(c + length, r)},
                {centre(c, r), centre(c - length, r + length), centre(c, r + length)},
                {centre(c, r), centre(c - length, r + length), centre(c - length, r)},
            };
            for (const auto& v : triangles) {
                TriangleSetup t;
                ASSERT_EQ(setup_triangle(v[0], v[1], v[2], CullMode::none, viewport, t), SetupResult::drawn);
                ASSERT_EQ(bool(t.small), length < 128);
                t.triangle = id++;
                for (int size : {16, 64})
                    for (const TileRect& rect : tiles(viewport.width, viewport.height, size)) {
                        if (!meets(t, rect)) continue;
                        buffers.clear(size);
                        rasterize_opaque(t, rect, buffers);
                        expect_alone(t, rect, buffers, true, covered);
                        if (HasFatalFailure()) return;
                    }
            }
        }
    EXPECT_GT(covered, 500000u);
}

// Huge triangles on the largest viewport, at tiles where their edges cross it (the big path's
// blocks, partly covered, with int64 edge values at the block corners far from the box's).
TEST(PipelineTileRaster, HugeTrianglesAtTheFarCornerOfTheLargestViewport) {
    const int size_px = kMaxViewport;
    const Viewport viewport(size_px, size_px);
    Rng rng(16302);
    TileBuffers buffers;
    size_t covered = 0;
    int checked = 0;
    while (checked < 150) {
        const test::RandomTriangle tri = test::random_triangle(rng, size_px, size_px, 16000, 4000);
        TriangleSetup t;
        if (setup_triangle(tri.v[0], tri.v[1], tri.v[2], CullMode::none, viewport, t) != SetupResult::drawn)
            continue;
        t.triangle = 7;
        // A tile on one of the edges, inside the viewport (biased to its far corner).
        const WindowVertex &a = tri.v[rng.uniform(0, 2)], &b = tri.v[rng.uniform(0, 2)];
        const double s = rng.unit();
        const double ex = (a.X + s * (b.X - a.X)) / 256.0, ey = (a.Y + s * (b.Y - a.Y)) / 256.0;
        const int size = kTileSizes[checked % 5];
        const int x = checked % 2 ? size_px - 1 - int(rng.uniform(0, 300)) : int(ex);
        const int y = checked % 2 ? size_px - 1 - int(rng.uniform(0, 300)) : int(ey);
        if (x < 0 || x >= size_px || y < 0 || y >= size_px) continue;
        const TileRect r{x & ~(size - 1), y & ~(size - 1), (x & ~(size - 1)) + size, (y & ~(size - 1)) + size};
        if (!meets(t, r)) continue;
        buffers.clear(size);
        rasterize_opaque(t, r, buffers);
        expect_alone(t, r, buffers, true, covered);
        if (HasFatalFailure()) return;
        ++checked;
    }
    EXPECT_GT(covered, 100000u);
}

// Brute force of a whole frame: triangles in submission order, depth test LESS on the depth
// offsets, at every pixel of the viewport; `depth` gets window depth.
void brute_force_frame(const std::vector<TriangleSetup>& setups, int w, int h, std::vector<uint32_t>& ids,
                       std::vector<float>& depth) {
    ids.assign(size_t(w) * h, kNoTriangle);
    std::vector<float> offset(size_t(w) * h, 0.0f);
    for (const TriangleSetup& t : setups)
        for (int y = t.miny; y <= t.maxy; ++y)
            for (int x = t.minx; x <= t.maxx; ++x) {
                const size_t i = size_t(y) * w + x;
                if (!setup_covers(t, x, y)) continue;
                const float z = depth_offset(t, x, y);
                if (z < offset[i]) offset[i] = z, ids[i] = t.triangle;
            }
    depth.resize(offset.size());
    std::transform(offset.begin(), offset.end(), depth.begin(), window_depth);
}

// Overlapping triangles through the tile buffers, flushed to a row-major frame (streamed where
// the rows are aligned), against the brute-force frame: the depth test and the flush. The
// third frame has only triangles at depth 0.5 (and a few at 1.0: depth offsets -0.5 and 0),
// which tie wherever they overlap, edge steps aside: the first one drawn keeps the pixel.
TEST(PipelineTileRaster, DepthTestedFramesMatchBruteForce) {
    Rng rng(16303);
    for (const auto& [w, h, flat] : {std::tuple{333, 259, false}, std::tuple{320, 240, false},  // 320: rows on cache lines
                                     std::tuple{200, 150, true}}) {
        Classes classes;
        std::vector<TriangleSetup> setups = random_setups(rng, w, h, flat ? 60 : 400, classes);
        for (TriangleSetup& t : setups)
            if (flat) t.depth = {0.0f, 0.0f, t.triangle % 8 ? -0.5f : 0.0f, t.depth.ax, t.depth.ay};
        std::vector<uint32_t> expected_ids;
        std::vector<float> expected_depth;
        brute_force_frame(setups, w, h, expected_ids, expected_depth);
        for (int size : kTileSizes)
            for (bool depth_only : {false, true})
                for (bool stream : {false, true}) {
                    AlignedVector<uint32_t> ids(size_t(w) * h, 0xABABABABu);
                    AlignedVector<float> depth(size_t(w) * h, -1.0f);
                    TileBuffers buffers;
                    buffers.clear(size);
                    for (const TileRect& r : tiles(w, h, size)) {
                        for (const TriangleSetup& t : setups) {
                            if (depth_only) rasterize_depth(t, r, buffers);
                            else rasterize_opaque(t, r, buffers);
                        }
                        const size_t origin = size_t(r.y0) * w + r.x0;
                        buffers.flush(r.x1 - r.x0, r.y1 - r.y0, depth_only ? nullptr : ids.data() + origin,
                                      depth.data() + origin, size_t(w), stream);
                    }
                    simd::stream_fence();
                    size_t id_mismatch = 0, depth_mismatch = 0;
                    for (size_t i = 0; i < ids.size(); ++i) {
                        const uint32_t id = depth_only ? 0xABABABABu : expected_ids[i];
                        id_mismatch += ids[i] != id;
                        depth_mismatch += std::bit_cast<uint32_t>(depth[i]) != std::bit_cast<uint32_t>(expected_depth[i]);
                    }
                    ASSERT_EQ(id_mismatch, 0u) << w << "x" << h << " tile " << size << " depth only " << depth_only;
                    ASSERT_EQ(depth_mismatch, 0u) << w << "x" << h << " tile " << size << " depth only " << depth_only;
                }
    }
}

// The depth of a covered pixel centre in exact arithmetic: the plane through the snapped
// vertices (barycentrics from the int64 edge functions, the sum in long double).
long double exact_depth(const WindowVertex v[3], int x, int y) {
    const int64_t px = test::pixel_centre(x), py = test::pixel_centre(y);
    return (static_cast<long double>(test::orient(v[1], v[2], px, py)) * v[0].z +
            static_cast<long double>(test::orient(v[2], v[0], px, py)) * v[1].z +
            static_cast<long double>(test::orient(v[0], v[1], px, py)) * v[2].z) /
           static_cast<long double>(test::orient(v[0], v[1], v[2].X, v[2].Y));
}

// Triangles whose depths all lie within 1e-6 of 0.995 (where window depths are 6e-8 apart),
// overlapping everywhere: at every pixel the tile rasterizer keeps a triangle whose exact depth
// there is the least, up to the rounding of the two planes' float evaluation in depth offsets
// (triangle_setup.h): 4 ulps of each of its terms a (x - ax), b (y - ay) and z - 1, 1e-9 here.
TEST(PipelineTileRaster, KeepsTheNearerByExactArithmetic) {
    const int w = 200, h = 150;
    const Viewport viewport(w, h);
    Rng rng(16306);
    std::vector<TriangleSetup> setups;
    std::vector<std::array<WindowVertex, 3>> vertices;
    while (setups.size() < 300) {
        test::RandomTriangle tri = test::random_triangle(rng, w, h, std::array{6, 30, 120}[setups.size() % 3]);
        for (WindowVertex& v : tri.v) v.z = 0.995f + 1e-6f * rng.unit();
        TriangleSetup t;
        if (setup_triangle(tri.v[0], tri.v[1], tri.v[2], CullMode::none, viewport, t) != SetupResult::drawn) continue;
        t.triangle = uint32_t(setups.size());
        setups.push_back(t);
        vertices.push_back({tri.v[0], tri.v[1], tri.v[2]});
    }
    AlignedVector<uint32_t> ids(size_t(w) * h);
    AlignedVector<float> depth(size_t(w) * h);
    TileBuffers buffers;
    buffers.clear(64);
    for (const TileRect& r : tiles(w, h, 64)) {
        for (const TriangleSetup& t : setups) rasterize_opaque(t, r, buffers);
        buffers.flush(r.x1 - r.x0, r.y1 - r.y0, ids.data() + size_t(r.y0) * w + r.x0,
                      depth.data() + size_t(r.y0) * w + r.x0, size_t(w), false);
    }
    const auto rounding = [&](const TriangleSetup& t, int x, int y, long double z) {
        const double dx = double(x - t.depth.ax), dy = double(y - t.depth.ay);
        return 4.0 * 0x1p-24 * (std::fabs(t.depth.a * dx) + std::fabs(t.depth.b * dy) + std::fabs(double(z - 1.0L)));
    };
    size_t farther = 0, close_calls = 0, checked = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const uint32_t kept = ids[size_t(y) * w + x];
            long double least = 2.0L;
            double least_rounding = 0.0;
            size_t second = 0;
            for (const TriangleSetup& t : setups) {
                if (x < t.minx || x > t.maxx || y < t.miny || y > t.maxy || !setup_covers(t, x, y)) continue;
                const long double z = exact_depth(vertices[t.triangle].data(), x, y);
                if (z < least) least = z, least_rounding = rounding(t, x, y, z);
                ++second;
            }
            if (kept == kNoTriangle) {
                ASSERT_EQ(least, 2.0L) << "pixel (" << x << ", " << y << ") covered but empty";
                continue;
            }
            const long double z = exact_depth(vertices[kept].data(), x, y);
            const double allowed = least_rounding + rounding(setups[kept], x, y, z);
            farther += double(z - least) > allowed;
            close_calls += second > 1 && double(z - least) <= 6e-8;  // within a float spacing near 1
            ++checked;
        }
    EXPECT_EQ(farther, 0u);
    EXPECT_GT(checked, size_t(w * h / 2));
    EXPECT_GT(close_calls, 1000u);
}

// A fold: two triangles on the same side of a shared edge that runs exactly through sample
// positions (vertical, horizontal, diagonal; through pixel centres, and through sample 3 of
// the 4x pattern at (2, 6) / 16), one deeper inside than the other. Both cover the samples on
// the edge (top-left rule) with exactly the same depth; there the one that is nearer just
// inside the edge, where coverage decided, must be kept, whichever was drawn first. (On a
// right or bottom edge neither covers them.)
TEST(PipelineTileRaster, FoldOverAnEdgeThroughSamplesKeepsTheNearerInside) {
    const Viewport viewport(128, 128);
    for (int samples : {1, 4}) {
        // Sample 0 of one sample at the centre; sample 3 of four at (2, 6) / 16 pixels from it.
        const int ox = samples == 1 ? 0 : 32, oy = samples == 1 ? 0 : 96, s = samples == 1 ? 0 : 3;
        const auto at = [&](int x, int y, float z) { return WindowVertex{x * 256 + 128 + ox, y * 256 + 128 + oy, z}; };
        // Edge a -> b, then the third vertices of the nearer and the deeper triangle.
        const WindowVertex folds[][4] = {
            {at(20, 20, 0.5f), at(20, 90, 0.6f), at(70, 55, 0.55f), at(45, 55, 0.7f)},   // vertical, inside right
            {at(90, 20, 0.5f), at(90, 90, 0.6f), at(40, 55, 0.55f), at(65, 55, 0.7f)},   // vertical, inside left
            {at(20, 20, 0.5f), at(90, 20, 0.6f), at(55, 70, 0.55f), at(55, 45, 0.7f)},   // horizontal, inside below
            {at(20, 90, 0.5f), at(90, 90, 0.6f), at(55, 40, 0.55f), at(55, 65, 0.7f)},   // horizontal, inside above
            {at(20, 20, 0.5f), at(90, 90, 0.6f), at(90, 30, 0.55f), at(70, 40, 0.72f)},  // diagonal
            {at(20, 20, 0.5f), at(90, 90, 0.6f), at(30, 90, 0.55f), at(40, 70, 0.72f)},
        };
        int on_edge = 0;
        for (const auto& f : folds)
            for (bool nearer_first : {true, false}) {
                TriangleSetup nearer, deeper;
                ASSERT_EQ(setup_triangle(f[0], f[1], f[2], CullMode::none, viewport, nearer, samples), SetupResult::drawn);
                ASSERT_EQ(setup_triangle(f[0], f[1], f[3], CullMode::none, viewport, deeper, samples), SetupResult::drawn);
                nearer.triangle = 1;
                deeper.triangle = 2;
                TileBuffers buffers;
                buffers.clear(128, samples);
                const TileRect r{0, 0, 128, 128};
                for (const TriangleSetup* t : nearer_first ? std::array{&nearer, &deeper} : std::array{&deeper, &nearer})
                    rasterize_opaque(*t, r, buffers);
                // Samples on the edge line: (x, y) on a -> b, with a the first pixel.
                const uint32_t expected = test::is_top_or_left(f[0], f[1], f[2]) ? 1u : kNoTriangle;
                const int dx = (f[1].X - f[0].X) / 256, dy = (f[1].Y - f[0].Y) / 256, n = std::max(std::abs(dx), std::abs(dy));
                for (int k = 1; k < n; ++k) {
                    const int x = f[0].X / 256 + k * (dx / n), y = f[0].Y / 256 + k * (dy / n);
                    const size_t i = size_t(s) * buffers.plane() + buffers.index(x, y);
                    ASSERT_EQ(buffers.triangle[i], expected) << "fold " << (&f - folds) << ", sample at pixel (" << x << ", "
                                                       << y << "), nearer drawn " << (nearer_first ? "first" : "second");
                    on_edge += expected == 1u;
                }
            }
        EXPECT_GT(on_edge, 400);
    }
}

// rasterize_tested: exactly the covered pixels whose window depth is LESS than a given
// row-major window depth buffer (ties fail), with window_depth(depth_offset(t, x, y)) to the
// bit (the depth buffer is const).
TEST(PipelineTileRaster, TestedFragmentsAreTheCoveredPixelsInFront) {
    const int w = 301, h = 203;
    Rng rng(16304);
    Classes classes;
    const std::vector<TriangleSetup> setups = random_setups(rng, w, h, 120, classes);
    std::vector<Fragment> fragments;
    size_t passed = 0, ties = 0;
    for (int size : {16, 64, 256})
        for (const TileRect& r : tiles(w, h, size)) {
            // Padded rows: a fragment past the tile's right edge would read the padding, where
            // everything passes.
            const size_t stride = size_t(r.x1 - r.x0) + 5;
            std::vector<float> depth(stride * size_t(r.y1 - r.y0), 2.0f);
            fragments.resize(size_t(size) * size);
            for (const TriangleSetup& t : setups) {
                if (!meets(t, r)) continue;
                // Random depths, and at some pixels the fragment's own depth or its neighbours
                // (only the box can be covered: fragments elsewhere show up as unexpected; the
                // buffer passes everything there).
                const int x0 = std::max<int>(r.x0, t.minx), x1 = std::min<int>(r.x1 - 1, t.maxx);
                const int y0 = std::max<int>(r.y0, t.miny), y1 = std::min<int>(r.y1 - 1, t.maxy);
                for (int y = y0; y <= y1; ++y)
                    for (int x = x0; x <= x1; ++x) {
                        const float z = setup_covers(t, x, y) ? window_depth(depth_offset(t, x, y)) : rng.unit();
                        float& d = depth[size_t(y - r.y0) * stride + size_t(x - r.x0)];
                        switch (rng.bits() % 6) {
                            case 0: d = z; break;
                            case 1: d = std::nextafter(z, 2.0f); break;
                            case 2: d = std::nextafter(z, -1.0f); break;
                            default: d = rng.unit(); break;
                        }
                    }
                const size_t n = rasterize_tested(t, r, depth.data(), stride, fragments.data());
                std::vector<std::tuple<int, int, uint32_t>> got, expected;
                for (size_t k = 0; k < n; ++k)
                    got.emplace_back(fragments[k].y, fragments[k].x, std::bit_cast<uint32_t>(fragments[k].depth));
                for (int y = y0; y <= y1; ++y)
                    for (int x = x0; x <= x1; ++x) {
                        if (!setup_covers(t, x, y)) continue;
                        const float z = window_depth(depth_offset(t, x, y));
                        const float d = depth[size_t(y - r.y0) * stride + size_t(x - r.x0)];
                        ties += z == d;
                        if (z < d) expected.emplace_back(y, x, std::bit_cast<uint32_t>(z));
                    }
                std::sort(got.begin(), got.end());
                ASSERT_EQ(got, expected) << "triangle " << t.triangle << " tile at (" << r.x0 << ", " << r.y0
                                         << ") size " << size;
                passed += n;
            }
        }
    EXPECT_GT(passed, 100000u);
    EXPECT_GT(ties, 10000u);
}

// rasterize_tested_samples against its one-sample-at-a-time reference: the same pixels, the
// same sample masks (only the tile surface's samples, each LESS than its own depth) and the
// same nearest depth to the bit, for every size class, 4, 8 and 16 samples, random surface
// masks and sample depths, some of them the fragment's own depth at the sample (ties fail).
TEST(PipelineTileRaster, TestedSampleFragmentsMatchTheReference) {
    const int w = 101, h = 71;
    Rng rng(40417);
    size_t passed = 0, partial = 0;
    std::vector<Fragment> fast, reference;
    for (int samples : {4, 8, 16}) {
        const std::vector<TriangleSetup> setups =
            test::random_setups(rng, Viewport(w, h), 30, {2, 6, 14, 40, 150, 16000}, samples);
        const auto pattern = sample_pattern(samples);
        const uint16_t all = uint16_t((1u << samples) - 1u);
        for (int size : {16, 64})
            for (const TileRect& r : tiles(w, h, size)) {
                const size_t area = size_t(r.width()) * size_t(r.height());
                std::vector<uint16_t> mask(area);
                std::vector<float> depth(area * size_t(samples));
                Tile tile;
                tile.rect = r;
                tile.stride = size_t(r.width());
                tile.sample_mask = mask.data();
                tile.sample_count = samples;
                tile.sample_offsets = sample_positions(samples);
                tile.sample_depth = depth.data();
                tile.sample_depth_row = size_t(r.width()) * size_t(samples);
                tile.sample_depth_pixel_step = size_t(samples);
                tile.sample_depth_sample_step = 1;
                fast.resize(area + simd::kLanes);
                reference.resize(area);
                for (const TriangleSetup& t : setups) {
                    if (!meets(t, r)) continue;
                    // Only the box can be covered: both paths read nothing else.
                    const int x0 = std::max<int>(r.x0, t.minx), x1 = std::min<int>(r.x1 - 1, t.maxx);
                    const int y0 = std::max<int>(r.y0, t.miny), y1 = std::min<int>(r.y1 - 1, t.maxy);
                    for (int y = y0; y <= y1; ++y)
                        for (int x = x0; x <= x1; ++x) {
                            const uint32_t pick = rng.bits() % 4;
                            mask[tile.offset(x, y)] = pick == 0 ? uint16_t(0) : pick == 1 ? uint16_t(rng.bits() & all) : all;
                            for (int s = 0; s < samples; ++s) {
                                const float z = window_depth(depth_offset_at_sample(t, x, y, pattern[s].x, pattern[s].y));
                                float& d = depth[tile.offset(x, y) * size_t(samples) + size_t(s)];
                                d = rng.bits() % 5 == 0 ? z : rng.unit();
                            }
                        }
                    const size_t n = rasterize_tested_samples(t, tile, fast.data());
                    const size_t m = rasterize_tested_samples_reference(t, tile, reference.data());
                    std::vector<std::tuple<int, int, uint16_t, uint32_t>> got, expected;
                    for (size_t k = 0; k < n; ++k)
                        got.emplace_back(fast[k].y, fast[k].x, fast[k].mask, std::bit_cast<uint32_t>(fast[k].depth));
                    for (size_t k = 0; k < m; ++k) {
                        expected.emplace_back(reference[k].y, reference[k].x, reference[k].mask,
                                              std::bit_cast<uint32_t>(reference[k].depth));
                        partial += reference[k].mask != mask[tile.offset(reference[k].x, reference[k].y)];
                    }
                    std::sort(got.begin(), got.end());
                    ASSERT_EQ(got, expected) << samples << " samples, triangle " << t.triangle << " tile at ("
                                             << r.x0 << ", " << r.y0 << ") size " << size;
                    passed += n;
                }
            }
    }
    EXPECT_GT(passed, 10000u);
    EXPECT_GT(partial, 3000u);
}

// The stamp layout: index() maps the tile's pixels one to one onto the buffers, each stamp's
// lanes contiguous with lane i at (i % kStampW, i / kStampW) from the stamp's corner (simd.h).
TEST(PipelineTileRaster, TileBufferIndexIsTheStampLayout) {
    for (int size : kTileSizes) {
        TileBuffers b;
        b.clear(size);
        std::vector<int> hits(size_t(size) * size, 0);
        for (int y = 0; y < size; ++y)
            for (int x = 0; x < size; ++x) {
                const size_t i = b.index(x, y);
                ASSERT_LT(i, hits.size());
                ++hits[i];
                const int lane = int(i % simd::kLanes);
                const size_t stamp = i / simd::kLanes;
                EXPECT_EQ(x % simd::kStampW, lane % simd::kStampW);
                EXPECT_EQ(y % simd::kStampH, lane / simd::kStampW);
                EXPECT_EQ(stamp, size_t(y / simd::kStampH) * size_t(size / simd::kStampW) + size_t(x / simd::kStampW));
            }
        EXPECT_TRUE(std::all_of(hits.begin(), hits.end(), [](int n) { return n == 1; }));
    }
}

// flush(): the tile's pixels [0, width) x [0, height) to rows of `stride` values (depth offsets
// as window depth), nothing else written, and the buffers cleared (depth offset 0, no
// triangle) for the next tile.
TEST(PipelineTileRaster, FlushCopiesTheTileToRowsAndClearsIt) {
    Rng rng(16305);
    for (int size : kTileSizes)
        for (const auto& [width, height] : {std::pair{size, size}, std::pair{size - 3, size - 1}, std::pair{1, 5}})
            for (bool stream : {false, true})
                for (bool with_ids : {true, false}) {
                    TileBuffers b;
                    b.clear(size);
                    for (size_t i = 0; i < b.depth.size(); ++i) {
                        b.depth[i] = -rng.unit();
                        b.triangle[i] = uint32_t(rng.bits());
                    }
                    const TileBuffers filled = b;
                    const size_t stride = size_t(size) + 16 * size_t(rng.uniform(0, 2));
                    const size_t rows = size_t(height) + 2;
                    AlignedVector<uint32_t> ids(stride * rows, 0x5A5A5A5Au);
                    AlignedVector<float> depth(stride * rows, -2.0f);
                    b.flush(width, height, with_ids ? ids.data() : nullptr, depth.data(), stride, stream);
                    simd::stream_fence();
                    for (size_t y = 0; y < rows; ++y)
                        for (size_t x = 0; x < stride; ++x) {
                            const bool in = int(x) < width && int(y) < height;
                            const size_t i = in ? filled.index(int(x), int(y)) : 0;
                            const uint32_t id = in && with_ids ? filled.triangle[i] : 0x5A5A5A5Au;
                            const float d = in ? window_depth(filled.depth[i]) : -2.0f;
                            ASSERT_EQ(ids[y * stride + x], id) << "size " << size << " pixel " << x << ", " << y;
                            ASSERT_EQ(depth[y * stride + x], d) << "size " << size << " pixel " << x << ", " << y;
                        }
                    EXPECT_TRUE(std::all_of(b.depth.begin(), b.depth.end(),
                                            [](float d) { return std::bit_cast<uint32_t>(d) == 0u; }));
                    if (with_ids) {
                        EXPECT_TRUE(std::all_of(b.triangle.begin(), b.triangle.end(),
                                                [](uint32_t id) { return id == kNoTriangle; }));
                    }
                }
}

}  // namespace
}  // namespace tessera::pipeline
