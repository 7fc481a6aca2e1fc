// The tile stage's side of binning (bin.h): the setups of a tile's bin entries, in order. An
// entry that names a stored setup is that setup; the deferred ones (triangle ids) are set up
// again, up to kLanes consecutive ones at a time, from the vertex stage's records with the
// primitive stage's own lanes setup (triangle_setup_lanes.h), so that each is the setup the
// primitive stage found drawn, bit for bit.
#pragma once
#include <algorithm>
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
    // Prefetches what set_up will read for the deferred entries among [begin, end): their
    // corner indices (`indices`) or, once those are at hand, their vertex records. The
    // triangles of a bin may lie anywhere in the mesh (a soup of triangles binned by
    // position): fetched on demand, each would wait for memory twice.
    void prefetch(const uint32_t* begin, const uint32_t* end, bool indices) const;
    uint8_t transparent(uint32_t id) const {
        return !options->transparent.empty() && options->transparent[id] ? 1 : 0;
    }
};

// Calls fn(const TriangleSetup&) for every entry in [begin, end) of `chunk`'s bins, in order.
template <class Fn>
void for_each_setup(const ChunkBins& chunk, const uint32_t* begin, const uint32_t* end, const SetupSource& source,
                    Fn&& fn) {
    SmallSetups small;
    // Two batches ahead the corner indices, one batch ahead (indices in cache by then) the
    // vertex records.
    constexpr int kAhead = simd::kLanes;
    source.prefetch(begin, std::min(end, begin + 2 * kAhead), true);
    source.prefetch(begin, std::min(end, begin + kAhead), false);
    const uint32_t* fetched = std::min(end, begin + kAhead);  // records prefetched below here
    for (const uint32_t* e = begin; e != end;) {
        if (fetched < end && fetched < e + kAhead) {
            const uint32_t* next = std::min(end, fetched + kAhead);
            source.prefetch(std::min(end, fetched + kAhead), std::min(end, next + kAhead), true);
            source.prefetch(fetched, next, false);
            fetched = next;
        }
        if (*e & kStoredSetup) {
            fn(chunk.setups[*e & ~kStoredSetup]);
            ++e;
            continue;
        }
        const uint32_t* run = e;
        int n = 0;
        while (e != end && !(*e & kStoredSetup) && n < simd::kLanes) ++e, ++n;
        source.set_up(run, n, small);
        for (int lane = 0; lane < n; ++lane) {
            TriangleSetup t;
            small.write(lane, t);
            t.triangle = run[lane];
            t.transparent = source.transparent(run[lane]);
            fn(t);
        }
    }
}

}  // namespace tessera::pipeline
