#include "raster/pipeline/deferred_setup.h"

#include <cassert>

namespace tessera::pipeline {

void SetupSource::set_up(const uint32_t* ids, int n, SmallSetups& out) const {
    using simd::vint;
    using simd::vmask;
    // The corners relative to the first triangle's: a bin's ids ascend within one chunk
    // (at most 65536 triangles), so the lane offsets stay small.
    alignas(64) int32_t offset[simd::kLanes] = {};
    for (int lane = 0; lane < n; ++lane) offset[lane] = int32_t(ids[lane] - ids[0]);
    const vmask active = simd::lane_index() < vint(n);
    WindowLanes w;
    vint codes;
    const vmask valid = gather_corners(mesh->indices.data() + 3 * size_t(ids[0]), vint::load(offset), active,
                                       mesh->triangle_count() - ids[0], vertices->projected.data(), vertices->size(),
                                       w, codes);
    const vmask rest = setup_small_triangles(w, valid, options->cull, *viewport, options->samples, out);
    // The primitive stage found these valid, inside the guard band, small and drawn.
    assert(simd::bits(valid) == simd::bits(active) && !simd::any(rest));
    (void)valid;
    (void)rest;
    (void)codes;
}

void SetupSource::prefetch(const uint32_t* begin, const uint32_t* end, bool indices) const {
    const uint32_t* corners = mesh->indices.data();
    const ProjectedVertex* records = vertices->projected.data();
    const size_t vertex_count = vertices->size();
    for (const uint32_t* e = begin; e < end; ++e) {
        if (*e & kStoredSetup) continue;
        const uint32_t* triangle = corners + 3 * size_t(*e);
        if (indices) {
            __builtin_prefetch(triangle);
            continue;
        }
        for (int k = 0; k < 3; ++k)
            if (triangle[k] < vertex_count) __builtin_prefetch(records + triangle[k]);
    }
}

}  // namespace tessera::pipeline
