#include "raster/pipeline/bin.h"

#include <bit>
#include <stdexcept>
#include <string>

namespace tessera::pipeline {

TileGrid::TileGrid(int w, int h, int tile_size) : size(tile_size), width(w), height(h) {
    if (tile_size < 16 || tile_size > 256 || !std::has_single_bit(unsigned(tile_size)))
        throw std::invalid_argument("tile size " + std::to_string(tile_size) +
                                    " must be a power of two in 16 .. 256");
    shift = std::countr_zero(unsigned(tile_size));
    tiles_x = (w + size - 1) >> shift;
    tiles_y = (h + size - 1) >> shift;
}

void ChunkBins::bin(const TileGrid& grid, std::vector<uint32_t>& count) {
    const int tiles = grid.count();
    count.assign(size_t(tiles) + 1, 0);
    // Pass 1: how many entries each tile gets (the tiles of each setup's box).
    for (const TriangleSetup& t : setups) {
        const int tx0 = t.minx >> grid.shift, tx1 = t.maxx >> grid.shift;
        const int ty0 = t.miny >> grid.shift, ty1 = t.maxy >> grid.shift;
        if (tx0 == tx1 && ty0 == ty1) {  // most triangles touch one tile
            ++count[size_t(ty0) * grid.tiles_x + tx0 + 1];
            continue;
        }
        for (int ty = ty0; ty <= ty1; ++ty)
            for (int tx = tx0; tx <= tx1; ++tx) ++count[size_t(ty) * grid.tiles_x + tx + 1];
    }
    // Prefix sums give each bin's start; pass 2 scatters in setup order (stable).
    offsets.resize(size_t(tiles) + 1);
    offsets[0] = 0;
    for (int t = 0; t < tiles; ++t) offsets[t + 1] = offsets[t] + count[t + 1];
    entries.resize(offsets[tiles]);
    for (int t = 0; t < tiles; ++t) count[t] = offsets[t];
    for (const TriangleSetup& s : setups) {
        const int tx0 = s.minx >> grid.shift, tx1 = s.maxx >> grid.shift;
        const int ty0 = s.miny >> grid.shift, ty1 = s.maxy >> grid.shift;
        if (tx0 == tx1 && ty0 == ty1) {
            entries[count[size_t(ty0) * grid.tiles_x + tx0]++] = s;
            continue;
        }
        for (int ty = ty0; ty <= ty1; ++ty)
            for (int tx = tx0; tx <= tx1; ++tx) entries[count[size_t(ty) * grid.tiles_x + tx]++] = s;
    }
}

}  // namespace tessera::pipeline
