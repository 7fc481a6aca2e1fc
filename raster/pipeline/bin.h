// Binning (README "One frame, as data flows", step 3): each chunk of triangles sorts its
// triangles into the bins of the screen tiles their pixel boxes touch. A chunk owns its bins,
// so no locks are needed, and the tile stage reads chunk 0's bin, then chunk 1's, ... which
// is submission order whatever the number of threads.
//
// A bin holds 4-byte entries. Most triangles of a detailed mesh are small and need no
// clipping: their entry is the triangle id alone, and the tile stage sets them up again,
// kLanes at a time (deferred_setup.h), from the vertex stage's records. The others (clipped
// or large triangles, and small ones whose neighbours in submission order scatter over the
// screen, so that a tile would read their corners from all over the mesh) are set up once
// by the primitive stage and copied whole into the bins, beside the entries, where the tile
// stage reads them in order. A 1M-triangle mesh thus bins 4 MB instead of 80 MB of setups
// that went out to memory and were read back, while a soup of triangles keeps its setups
// streaming (BENCHMARKS.md: binning indices into the frame's setups missed the cache on
// every triangle; copying every setup moved 80 bytes per triangle twice).
#pragma once
#include <cstdint>
#include <span>
#include <vector>

#include "raster/core/tile.h"
#include "raster/pipeline/triangle_setup.h"

namespace tessera::pipeline {

// A bin entry with this bit set stands for the next of the bin's setup copies; without it, it
// is the id of a triangle whose setup is deferred to the tile stage.
inline constexpr uint32_t kStoredSetup = 0x80000000u;

// What the primitive stage hands to binning per drawn triangle: its entry (a triangle id, or
// kStoredSetup | the index of its setup among the chunk's stored setups) and pixel box.
struct BinItem {
    uint32_t entry;
    int16_t minx, miny, maxx, maxy;  // inclusive, within the viewport
};

// One chunk's per-tile bins (counting-sorted by tile).
struct ChunkBins {
    std::vector<uint32_t> entries;     // grouped by tile, in submission order per tile
    std::vector<uint32_t> offsets;     // bin of tile t = entries[offsets[t] .. offsets[t+1])
    std::vector<TriangleSetup> copies; // the stored setups of tile t's entries, in order, from
    std::vector<uint32_t> copy_offsets;  // copies[copy_offsets[t]]

    // Builds the bins from the chunk's `items` (in submission order, as the primitive stage
    // made them) and the `setups` their stored entries name, for `grid` (tiles of a
    // power-of-two size). `scratch` is reused storage. Items and setups are needed only until
    // then: the rasterizer keeps them in buffers per thread, reused chunk after chunk, so that
    // they stay in cache.
    void bin(std::span<const BinItem> items, std::span<const TriangleSetup> setups, const TileGrid& grid,
             std::vector<uint32_t>& scratch);

    const uint32_t* begin(int tile) const { return entries.data() + offsets[tile]; }
    const uint32_t* end(int tile) const { return entries.data() + offsets[tile + 1]; }
    const TriangleSetup* stored(int tile) const { return copies.data() + copy_offsets[tile]; }
};

}  // namespace tessera::pipeline
