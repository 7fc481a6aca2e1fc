#include "raster/pipeline/bin.h"

#include <bit>
#include <stdexcept>
#include <string>

namespace tessera::pipeline {

void ChunkBins::bin(std::span<const BinItem> items, std::span<const TriangleSetup> setups, const TileGrid& grid,
                    std::vector<uint32_t>& count) {
    if (!std::has_single_bit(unsigned(grid.size)))
        throw std::invalid_argument("binning needs tiles of a power-of-two size, not " + std::to_string(grid.size));
    const int shift = std::countr_zero(unsigned(grid.size));
    const size_t tiles = size_t(grid.count());
    // count[t + 1]: entries of tile t; count[tiles + 2 + t]: its stored setups.
    count.assign(2 * tiles + 2, 0);
    uint32_t* entry_count = count.data();
    uint32_t* copy_count = count.data() + tiles + 1;
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
    // Pass 1: how many entries and copies each tile gets (the tiles of each item's box).
    uint32_t run_tile = 0, run = 0;
    for (const BinItem& t : items) {
        const uint32_t tile = tile_of(t);
        const bool stored = t.entry & kStoredSetup;
        if (tile == run_tile) {
            ++run;
            copy_count[tile + 1] += stored;
            continue;
        }
        entry_count[run_tile + 1] += run;
        run = 0;
        if (tile == kSeveral) {
            for_each_tile(t, [&](size_t i) { ++entry_count[i + 1], copy_count[i + 1] += stored; });
        } else {
            run_tile = tile, run = 1;
            copy_count[tile + 1] += stored;
        }
    }
    entry_count[run_tile + 1] += run;
    // Prefix sums give each bin's start; pass 2 scatters in item order (stable).
    offsets.resize(tiles + 1);
    copy_offsets.resize(tiles + 1);
    offsets[0] = copy_offsets[0] = 0;
    for (size_t t = 0; t < tiles; ++t) {
        offsets[t + 1] = offsets[t] + entry_count[t + 1];
        copy_offsets[t + 1] = copy_offsets[t] + copy_count[t + 1];
    }
    entries.resize(offsets[tiles]);
    copies.resize(copy_offsets[tiles]);
    for (size_t t = 0; t < tiles; ++t) entry_count[t] = offsets[t], copy_count[t] = copy_offsets[t];
    uint32_t* out = entries.data();
    TriangleSetup* copy = copies.data();
    const auto put = [&](const BinItem& t, uint32_t& cursor, uint32_t& copy_cursor) {
        if (t.entry & kStoredSetup) {
            out[cursor++] = kStoredSetup;
            copy[copy_cursor++] = setups[t.entry & ~kStoredSetup];
        } else {
            out[cursor++] = t.entry;
        }
    };
    run_tile = 0;
    uint32_t cursor = entry_count[0];
    for (const BinItem& t : items) {
        const uint32_t tile = tile_of(t);
        if (tile == run_tile) {
            put(t, cursor, copy_count[tile]);
            continue;
        }
        entry_count[run_tile] = cursor;
        if (tile == kSeveral) {
            for_each_tile(t, [&](size_t i) { put(t, entry_count[i], copy_count[i]); });
            cursor = entry_count[run_tile];
        } else {
            run_tile = tile;
            cursor = entry_count[run_tile];
            put(t, cursor, copy_count[tile]);
        }
    }
    entry_count[run_tile] = cursor;
}

}  // namespace tessera::pipeline
