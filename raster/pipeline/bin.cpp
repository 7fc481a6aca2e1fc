#include "raster/pipeline/bin.h"

#include <bit>
#include <stdexcept>
#include <string>

namespace tessera::pipeline {

void ChunkBins::bin(std::span<const TriangleSetup> setups, const TileGrid& grid, std::vector<uint32_t>& count) {
    if (!std::has_single_bit(unsigned(grid.size)))
        throw std::invalid_argument("binning needs tiles of a power-of-two size, not " + std::to_string(grid.size));
    const int shift = std::countr_zero(unsigned(grid.size));
    const int tiles = grid.count();
    count.assign(size_t(tiles) + 1, 0);
    // Pass 1: how many entries each tile gets (the tiles of each setup's box).
    for (const TriangleSetup& t : setups) {
        const int tx0 = t.minx >> shift, tx1 = t.maxx >> shift;
        const int ty0 = t.miny >> shift, ty1 = t.maxy >> shift;
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
        const int tx0 = s.minx >> shift, tx1 = s.maxx >> shift;
        const int ty0 = s.miny >> shift, ty1 = s.maxy >> shift;
        if (tx0 == tx1 && ty0 == ty1) {
            entries[count[size_t(ty0) * grid.tiles_x + tx0]++] = s;
            continue;
        }
        for (int ty = ty0; ty <= ty1; ++ty)
            for (int tx = tx0; tx <= tx1; ++tx) entries[count[size_t(ty) * grid.tiles_x + tx]++] = s;
    }
}

}  // namespace tessera::pipeline
