#include "raster/pipeline/bin.h"

#include <bit>
#include <stdexcept>
#include <string>

namespace tessera::pipeline {

void ChunkBins::bin(std::span<const BinItem> items, const TileGrid& grid, std::vector<uint32_t>& count) {
    if (!std::has_single_bit(unsigned(grid.size)))
        throw std::invalid_argument("binning needs tiles of a power-of-two size, not " + std::to_string(grid.size));
    const int shift = std::countr_zero(unsigned(grid.size));
    const int tiles = grid.count();
    count.assign(size_t(tiles) + 1, 0);
    // Consecutive triangles of a mesh mostly fall into one tile: a run of them is counted,
    // and later written, with its tile's counter in a register rather than incremented in
    // memory item after item (each increment would wait for the previous one's store).
    constexpr uint32_t kSeveral = ~0u;  // the item's box meets more than one tile
    const auto tile_of = [&](const BinItem& t) {
        const int tx0 = t.minx >> shift, tx1 = t.maxx >> shift;
        const int ty0 = t.miny >> shift, ty1 = t.maxy >> shift;
        return tx0 == tx1 && ty0 == ty1 ? uint32_t(ty0 * grid.tiles_x + tx0) : kSeveral;
    };
    const auto for_each_tile = [&](const BinItem& t, auto&& fn) {
        for (int ty = t.miny >> shift; ty <= t.maxy >> shift; ++ty)
            for (int tx = t.minx >> shift; tx <= t.maxx >> shift; ++tx) fn(size_t(ty) * grid.tiles_x + tx);
    };
    // Pass 1: how many entries each tile gets (the tiles of each item's box).
    uint32_t run_tile = 0, run = 0;
    for (const BinItem& t : items) {
        const uint32_t tile = tile_of(t);
        if (tile == run_tile) {
            ++run;
            continue;
        }
        count[run_tile + 1] += run;
        run = 0;
        if (tile == kSeveral) for_each_tile(t, [&](size_t i) { ++count[i + 1]; });
        else run_tile = tile, run = 1;
    }
    count[run_tile + 1] += run;
    // Prefix sums give each bin's start; pass 2 scatters in item order (stable).
    offsets.resize(size_t(tiles) + 1);
    offsets[0] = 0;
    for (int t = 0; t < tiles; ++t) offsets[t + 1] = offsets[t] + count[t + 1];
    entries.resize(offsets[tiles]);
    for (int t = 0; t < tiles; ++t) count[t] = offsets[t];
    uint32_t* out = entries.data();
    run_tile = 0;
    uint32_t cursor = count[0];
    for (const BinItem& t : items) {
        const uint32_t tile = tile_of(t);
        if (tile == run_tile) {
            out[cursor++] = t.entry;
            continue;
        }
        count[run_tile] = cursor;
        if (tile == kSeveral) {
            for_each_tile(t, [&](size_t i) { out[count[i]++] = t.entry; });
            cursor = count[run_tile];
        } else {
            run_tile = tile;
            cursor = count[run_tile];
            out[cursor++] = t.entry;
        }
    }
    count[run_tile] = cursor;
}

}  // namespace tessera::pipeline
