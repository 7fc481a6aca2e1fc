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

void SetupSource::prefetch_records(uint32_t entry) const {
    if (entry & kStoredSetup) return;
    const uint32_t* triangle = mesh->indices.data() + 3 * size_t(entry);
    const ProjectedVertex* records = vertices->projected.data();
    const size_t vertex_count = vertices->size();
    for (int k = 0; k < 3; ++k)
        if (triangle[k] < vertex_count) __builtin_prefetch(records + triangle[k]);
}

}  // namespace tessera::pipeline
