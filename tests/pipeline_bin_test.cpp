// Binning (raster/pipeline/bin.h) against a brute-force assignment: each tile's bin holds
// exactly the entries of the setups whose pixel box meets the tile, in submission order, so
// every tile a triangle covers a pixel of gets it; for every tile size and partial tiles at
// the borders.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <stdexcept>
#include <vector>

#include "pipeline_fixtures.h"
#include "raster/pipeline/bin.h"

namespace tessera::pipeline {
namespace {

using test::Rng;

// The bin items of `setups` (whose triangle ids are their indices): each names its setup, or
// with `deferred`, the odd ones are deferred (their triangle id).
std::vector<BinItem> items_of(const std::vector<TriangleSetup>& setups, bool deferred = false) {
    std::vector<BinItem> items;
    for (size_t i = 0; i < setups.size(); ++i) {
        const uint32_t entry = deferred && i % 2 ? setups[i].triangle : kStoredSetup | uint32_t(i);
        items.push_back({entry, setups[i].minx, setups[i].miny, setups[i].maxx, setups[i].maxy});
    }
    return items;
}

// Bins of `chunk` against the definition: tile t's bin is the subsequence of the setups whose
// box [minx, maxx] x [miny, maxy] meets the tile's pixels: stored entries, each beside its
// setup's copy, or with `deferred` (odd setups), its triangle id.
void expect_bins(const ChunkBins& chunk, const std::vector<TriangleSetup>& setups, const TileGrid& grid, bool deferred) {
    ASSERT_EQ(chunk.offsets.size(), size_t(grid.count()) + 1);
    ASSERT_EQ(chunk.offsets.front(), 0u);
    ASSERT_EQ(chunk.offsets.back(), chunk.entries.size());
    ASSERT_EQ(chunk.copy_offsets.back(), chunk.copies.size());
    for (int tile = 0; tile < grid.count(); ++tile) {
        const int x0 = (tile % grid.tiles_x) * grid.size, y0 = (tile / grid.tiles_x) * grid.size;
        const int x1 = std::min(x0 + grid.size, grid.width), y1 = std::min(y0 + grid.size, grid.height);
        const uint32_t* e = chunk.begin(tile);
        const TriangleSetup* copy = chunk.stored(tile);
        for (size_t i = 0; i < setups.size(); ++i) {
            const TriangleSetup& s = setups[i];
            if (s.maxx < x0 || s.minx >= x1 || s.maxy < y0 || s.miny >= y1) continue;
            ASSERT_LT(e, chunk.end(tile)) << "tile " << tile << " misses triangle " << s.triangle;
            if (deferred && i % 2) {
                ASSERT_EQ(*e, s.triangle) << "tile " << tile << " (submission order)";
            } else {
                ASSERT_EQ(*e, kStoredSetup) << "tile " << tile;
                ASSERT_EQ(std::memcmp(copy, &s, sizeof s), 0) << "tile " << tile << ": setup of triangle "
                                                             << copy->triangle << " where " << s.triangle
                                                             << " belongs (submission order)";
                ++copy;
            }
            ++e;
        }
        ASSERT_EQ(e, chunk.end(tile)) << "tile " << tile << " holds an entry whose box does not meet it";
        ASSERT_EQ(copy, tile + 1 < grid.count() ? chunk.stored(tile + 1) : chunk.copies.data() + chunk.copies.size());
    }
}

// Every covered pixel of every triangle finds the triangle in its tile's bin.
void expect_coverage_binned(const ChunkBins& chunk, const std::vector<TriangleSetup>& setups, const TileGrid& grid) {
    const size_t n = setups.size();
    std::vector<char> binned(size_t(grid.count()) * n, 0);  // [tile][triangle]
    for (int tile = 0; tile < grid.count(); ++tile) {
        const TriangleSetup* copy = chunk.stored(tile);
        for (const uint32_t* e = chunk.begin(tile); e != chunk.end(tile); ++e)
            binned[tile * n + (*e == kStoredSetup ? (copy++)->triangle : *e)] = 1;
    }
    for (const TriangleSetup& s : setups)
        for (int y = s.miny; y <= s.maxy; ++y)
            for (int x = s.minx; x <= s.maxx; ++x) {
                const size_t tile = size_t(y / grid.size) * grid.tiles_x + size_t(x / grid.size);
                if (test::setup_covers(s, x, y)) {
                    ASSERT_TRUE(binned[tile * n + s.triangle]) << "pixel (" << x << ", " << y << ") of triangle "
                                                                << s.triangle;
                }
            }
}

TEST(PipelineBin, TileGridCoversTheViewportAndBinningNeedsPowerOfTwoTiles) {
    for (int size : {16, 32, 64, 128, 256}) {
        const TileGrid g(1000, 17, size);
        EXPECT_EQ(g.tiles_x, (1000 + size - 1) / size);
        EXPECT_EQ(g.tiles_y, (17 + size - 1) / size);
        EXPECT_EQ(g.count(), g.tiles_x * g.tiles_y);
        const TileRect last = g.rect(g.count() - 1);  // the partial tile at the far corner
        EXPECT_EQ(last.x1, 1000);
        EXPECT_EQ(last.y1, 17);
    }
    EXPECT_EQ(TileGrid(256, 256, 256).count(), 1);
    EXPECT_EQ(TileGrid(257, 1, 256).count(), 2);
    ChunkBins chunk;
    std::vector<uint32_t> scratch;
    for (int bad : {24, 100, 96})
        EXPECT_THROW(chunk.bin({}, {}, TileGrid(640, 480, bad), scratch), std::invalid_argument) << bad;
}

TEST(PipelineBin, EveryTileGetsExactlyTheTrianglesThatMeetItInSubmissionOrder) {
    Rng rng(16201);
    std::vector<uint32_t> scratch;  // reused across grids, as the rasterizer reuses it
    for (const auto& [w, h] : {std::pair{301, 217}, std::pair{256, 128}, std::pair{1000, 37}}) {
        ChunkBins chunk;
        const std::vector<TriangleSetup> setups =
            test::random_setups(rng, Viewport(w, h), 300, {1, 4, 20, 70, 300, 16000});
        for (int size : {16, 32, 64, 128, 256}) {
            const TileGrid grid(w, h, size);
            for (bool deferred : {false, true}) {
                chunk.bin(items_of(setups, deferred), setups, grid, scratch);
                expect_bins(chunk, setups, grid, deferred);
                if (HasFatalFailure()) return;
            }
            if (HasFatalFailure()) return;
            expect_coverage_binned(chunk, setups, grid);
            if (HasFatalFailure()) return;
        }
    }
}

// Boxes ending exactly on either side of a tile border, and boxes of one pixel.
TEST(PipelineBin, BoxesAtTileBorders) {
    const int w = 200, h = 150;
    const TileGrid grid(w, h, 32);
    ChunkBins chunk;
    std::vector<TriangleSetup> setups;
    for (int edge : {31, 32, 63, 64, 127, 128, 149, 199}) {
        TriangleSetup s{};
        s.minx = int16_t(std::min(edge, w - 1));
        s.maxx = s.minx;
        s.miny = int16_t(std::min(edge, h - 1));
        s.maxy = s.miny;
        s.triangle = uint32_t(setups.size());
        setups.push_back(s);
        s.minx = int16_t(std::max(0, edge - 1));
        s.maxx = int16_t(std::min(edge + 1, w - 1));
        s.miny = 0;
        s.maxy = int16_t(h - 1);
        s.triangle = uint32_t(setups.size());
        setups.push_back(s);
    }
    std::vector<uint32_t> scratch;
    chunk.bin(items_of(setups), setups, grid, scratch);
    expect_bins(chunk, setups, grid, false);

    // No setups: every bin empty.
    ChunkBins none;
    none.bin({}, {}, grid, scratch);
    ASSERT_EQ(none.offsets.size(), size_t(grid.count()) + 1);
    for (int t = 0; t < grid.count(); ++t) EXPECT_EQ(none.begin(t), none.end(t));
}

}  // namespace
}  // namespace tessera::pipeline
