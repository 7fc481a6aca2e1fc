// Binning (README "One frame, as data flows", step 3): each chunk of triangles copies every
// triangle setup into the bins of the screen tiles its box touches. A chunk owns its bins, so
// no locks are needed, and the tile stage reads chunk 0's bin, then chunk 1's, ... which is
// submission order whatever the number of threads.
//
// Bins hold the setups themselves, not indices: the tile stage then streams each bin
// sequentially instead of gathering records scattered over the whole frame's setups (one cache
// and TLB miss per triangle, measured as the dominant cost of the first version).
#pragma once
#include <cstdint>
#include <span>
#include <vector>

#include "raster/core/tile.h"
#include "raster/pipeline/triangle_setup.h"

namespace tessera::pipeline {

// One chunk's per-tile bins of triangle setups (counting-sorted by tile).
struct ChunkBins {
    std::vector<TriangleSetup> entries;  // copies grouped by tile, in setup order per tile
    std::vector<uint32_t> offsets;       // bin of tile t = entries[offsets[t] .. offsets[t+1])

    // Builds entries/offsets from the chunk's `setups` (in submission order, as the primitive
    // stage made them) for `grid` (tiles of a power-of-two size). `scratch` is reused storage.
    // The setups are needed only until then: the rasterizer keeps them in a buffer per thread,
    // reused chunk after chunk, so that they stay in cache instead of going out to memory.
    void bin(std::span<const TriangleSetup> setups, const TileGrid& grid, std::vector<uint32_t>& scratch);

    const TriangleSetup* begin(int tile) const { return entries.data() + offsets[tile]; }
    const TriangleSetup* end(int tile) const { return entries.data() + offsets[tile + 1]; }
};

}  // namespace tessera::pipeline
