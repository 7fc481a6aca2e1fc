// Binning (README "One frame, as data flows", step 3): each chunk of triangles sorts its
// triangles into the bins of the screen tiles their pixel boxes touch. A chunk owns its bins,
// so no locks are needed, and the tile stage reads chunk 0's bin, then chunk 1's, ... which
// is submission order whatever the number of threads.
//
// A bin holds 4-byte entries. Most triangles of a detailed mesh are small and need no
// clipping: their entry is the triangle id alone, and the tile stage sets them up again,
// kLanes at a time (deferred_setup.h), from the vertex stage's records. Only the others
// (clipped or large) are set up once in the primitive stage and stored with the chunk; their
// entry names that setup. A 1M-triangle frame thus bins 4 MB instead of the 80 MB of whole
// setups, which went out to memory and were read back (the first version binned indices
// into the frame's setups and missed the cache on every triangle; the second copied setups
// into the bins; measured in BENCHMARKS.md).
#pragma once
#include <cstdint>
#include <span>
#include <vector>

#include "raster/core/tile.h"
#include "raster/pipeline/triangle_setup.h"

namespace tessera::pipeline {

// A bin entry with this bit set names ChunkBins::setups[entry & ~kStoredSetup]; without it,
// it is the id of a triangle whose setup is deferred to the tile stage.
inline constexpr uint32_t kStoredSetup = 0x80000000u;

// What the primitive stage hands to binning per drawn triangle: its entry and pixel box.
struct BinItem {
    uint32_t entry;
    int16_t minx, miny, maxx, maxy;  // inclusive, within the viewport
};

// One chunk's per-tile bins (counting-sorted by tile) and the setups its entries name.
struct ChunkBins {
    std::vector<TriangleSetup> setups;  // made by the primitive stage (clipped, large triangles)
    std::vector<uint32_t> entries;      // grouped by tile, in submission order per tile
    std::vector<uint32_t> offsets;      // bin of tile t = entries[offsets[t] .. offsets[t+1])

    // Builds entries/offsets from the chunk's `items` (in submission order, as the primitive
    // stage made them) for `grid` (tiles of a power-of-two size). `scratch` is reused storage.
    // The items are needed only until then: the rasterizer keeps them in a buffer per thread,
    // reused chunk after chunk, so that they stay in cache.
    void bin(std::span<const BinItem> items, const TileGrid& grid, std::vector<uint32_t>& scratch);

    const uint32_t* begin(int tile) const { return entries.data() + offsets[tile]; }
    const uint32_t* end(int tile) const { return entries.data() + offsets[tile + 1]; }
};

}  // namespace tessera::pipeline
