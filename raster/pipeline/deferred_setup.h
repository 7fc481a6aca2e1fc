// The tile stage's side of binning (bin.h): the setups of a tile's bin entries, in order. A
// stored entry is the bin's next setup copy; the deferred ones (triangle ids) are set up
// again, up to kLanes consecutive ones at a time, from the vertex stage's records with the
// primitive stage's own lanes setup (triangle_setup_lanes.h), so that each is the setup the
// primitive stage found drawn, bit for bit.
#pragma once
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <span>

#include "raster/core/mesh.h"
#include "raster/pipeline/bin.h"
#include "raster/pipeline/raster_options.h"
#include "raster/pipeline/triangle_setup.h"
#include "raster/pipeline/triangle_setup_lanes.h"
#include "raster/pipeline/vertex_stage.h"
#include "raster/pipeline/viewport.h"

namespace tessera::pipeline {

// What a deferred setup is made from: the render's mesh, vertex stage output and options.
struct SetupSource {
    const Mesh* mesh = nullptr;
    const ClipVertices* vertices = nullptr;
    const Viewport* viewport = nullptr;
    const RasterOptions* options = nullptr;

    // The setups of the n <= kLanes deferred entries `ids` (ascending, as a bin holds them).
    void set_up(const uint32_t* ids, int n, SmallSetups& out) const;
    // Prefetches what set_up will read for a deferred entry: its corner indices, or, once
    // those are at hand, its vertex records. The triangles of a bin may lie anywhere in the
    // mesh (a soup of triangles binned by position): fetched on demand, each would wait for
    // memory twice.
    void prefetch_indices(uint32_t entry) const {
        if (!(entry & kStoredSetup)) __builtin_prefetch(mesh->indices.data() + 3 * size_t(entry));
    }
    void prefetch_records(uint32_t entry) const;
    uint8_t transparent(uint32_t id) const {
        return !options->transparent.empty() && options->transparent[id] ? 1 : 0;
    }
};

// Calls fn(const TriangleSetup&) for every entry of `chunk`'s bin of `tile`, in order.
template <class Fn>
void for_each_setup(const ChunkBins& chunk, int tile, const SetupSource& source, Fn&& fn) {
    const uint32_t* begin = chunk.begin(tile);
    const uint32_t* end = chunk.end(tile);
    const TriangleSetup* stored = chunk.stored(tile);
    SmallSetups small;
    // One prefetch of each kind per triangle drawn, spread out so that they do not queue up
    // for the cache's miss buffers: indices 2 kAhead entries ahead, records kAhead ahead.
    // (Counts, not pointers past the bin: an empty bin's pointers are null.)
    constexpr ptrdiff_t kAhead = simd::kLanes;
    const ptrdiff_t count = end - begin;
    for (ptrdiff_t i = 0; i < std::min(count, 2 * kAhead); ++i) source.prefetch_indices(begin[i]);
    for (ptrdiff_t i = 0; i < std::min(count, kAhead); ++i) source.prefetch_records(begin[i]);
    const auto ahead = [&](const uint32_t* p) {
        const ptrdiff_t left = end - p;
        if (2 * kAhead < left) source.prefetch_indices(p[2 * kAhead]);
        if (kAhead < left) source.prefetch_records(p[kAhead]);
    };
    for (const uint32_t* e = begin; e != end;) {
        if (*e & kStoredSetup) {
            ahead(e);
            fn(*stored++);
            ++e;
            continue;
        }
        const uint32_t* run = e;
        int n = 0;
        while (e != end && !(*e & kStoredSetup) && n < simd::kLanes) ++e, ++n;
        source.set_up(run, n, small);
        for (int lane = 0; lane < n; ++lane) {
            ahead(run + lane);
            TriangleSetup t;
            small.write(lane, t);
            t.triangle = run[lane];
            t.transparent = source.transparent(run[lane]);
            fn(t);
        }
    }
}

}  // namespace tessera::pipeline
