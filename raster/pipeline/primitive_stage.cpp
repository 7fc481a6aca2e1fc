#include "raster/pipeline/primitive_stage.h"

#include "raster/pipeline/clip.h"
#include "raster/pipeline/triangle_setup_lanes.h"

#include <algorithm>
#include <bit>
#include <cstddef>

namespace tessera::pipeline {

namespace {

void count(SetupResult result, RasterStats& stats) {
    switch (result) {
        case SetupResult::drawn: ++stats.setups; break;
        case SetupResult::zero_area: ++stats.zero_area; break;
        case SetupResult::culled_face: ++stats.culled_face; break;
        case SetupResult::no_samples: ++stats.no_samples; break;
    }
}

}  // namespace

namespace {

// Appends a drawn setup to `setups` and its bin item to `items`.
void store(const TriangleSetup& setup, std::vector<BinItem>& items, std::vector<TriangleSetup>& setups) {
    items.push_back({kStoredSetup | uint32_t(setups.size()), setup.minx, setup.miny, setup.maxx, setup.maxy});
    setups.push_back(setup);
}

// The scalar path for triangle t with vertex indices i0 i1 i2 (each below the vertex count):
// reject, clip, or set up and store.
void primitive(const ClipVertices& v, const Viewport& viewport, const RasterOptions& options, uint32_t t,
               uint32_t i0, uint32_t i1, uint32_t i2, uint8_t transparent, std::vector<BinItem>& items,
               std::vector<TriangleSetup>& setups, RasterStats& stats) {
    const uint32_t c0 = v.projected[i0].code, c1 = v.projected[i1].code, c2 = v.projected[i2].code;
    const uint32_t codes = c0 | c1 | c2;
    if (codes & kClipInvalid) {
        ++stats.invalid;
        return;
    }
    if (c0 & c1 & c2) {
        ++stats.outside;
        return;
    }
    TriangleSetup setup;
    if (codes == 0) {
        const SetupResult result = setup_triangle(v.projected[i0].window, v.projected[i1].window,
                                                  v.projected[i2].window, options.cull, viewport, setup, options.samples);
        count(result, stats);
        if (result == SetupResult::drawn) {
            setup.triangle = t;
            setup.transparent = transparent;
            store(setup, items, setups);
        }
        return;
    }
    ++stats.clipped;
    const glm::vec4 in[3] = {v.clip(i0), v.clip(i1), v.clip(i2)};
    glm::vec4 polygon[kMaxClippedVertices];
    const int n = clip_triangle(in, codes, viewport, polygon);
    if (n < 3) return;  // nothing left inside: counted as clipped
    WindowVertex w[kMaxClippedVertices];
    for (int i = 0; i < n; ++i) w[i] = project_and_snap(viewport, polygon[i]);
    // The clipped polygon is convex: a fan from its first vertex keeps the winding.
    for (int i = 1; i + 1 < n; ++i) {
        const SetupResult result = setup_triangle(w[0], w[i], w[i + 1], options.cull, viewport, setup, options.samples);
        count(result, stats);
        if (result == SetupResult::drawn) {
            setup.triangle = t;
            setup.transparent = transparent;
            store(setup, items, setups);
        }
    }
}

}  // namespace

void run_primitive_stage(const Mesh& mesh, const ClipVertices& v, const Viewport& viewport,
                         const RasterOptions& options, uint32_t first, uint32_t last, std::vector<BinItem>& items,
                         std::vector<TriangleSetup>& setups, RasterStats& stats, bool store_all) {
    using simd::kLanes;
    using simd::vint;
    using simd::vmask;
    const uint32_t* indices = mesh.indices.data();
    const size_t vertex_count = v.size();
    const bool any_transparent = !options.transparent.empty();
    stats.triangles += last - first;
    if (vertex_count == 0) {  // every index is out of range
        stats.invalid += last - first;
        return;
    }
    const auto transparent = [&](uint32_t t) -> uint8_t { return any_transparent && options.transparent[t] ? 1 : 0; };
    if (vertex_count > kMaxLanesVertices) {
        for (uint32_t t = first; t < last; ++t) {
            const uint32_t i0 = indices[3 * size_t(t)], i1 = indices[3 * size_t(t) + 1], i2 = indices[3 * size_t(t) + 2];
            if (i0 >= vertex_count || i1 >= vertex_count || i2 >= vertex_count) ++stats.invalid;
            else primitive(v, viewport, options, t, i0, i1, i2, transparent(t), items, setups, stats);
        }
        return;
    }
    items.reserve(items.size() + (last - first));
    SmallSetups small;
    const int tile_shift = std::countr_zero(unsigned(options.tile_size));
    const int32_t tiles_x = (viewport.width + options.tile_size - 1) / options.tile_size;
    // kLanes triangles at a time: those whose corners all lie inside the guard band, and whose
    // vertex box is small, are set up in lanes (triangle_setup_lanes.h); the others, in
    // submission order between them, by the scalar path.
    for (uint32_t t = first; t < last; t += kLanes) {
        const int n = int(std::min<uint32_t>(kLanes, last - t));
        const vmask active = simd::lane_index() < vint(n);
        WindowLanes w;
        vint codes;
        const vmask valid = gather_corners(indices + 3 * size_t(t), simd::lane_index(), active,
                                           mesh.triangle_count() - t, v.projected.data(), vertex_count, w, codes);
        const vmask inside = valid & (codes == vint(0));
        const uint32_t scalar =
            simd::bits(classify_small_triangles(w, inside, options.cull, viewport, options.samples, small));
        const uint32_t fast = simd::bits(inside) & ~scalar, is_valid = simd::bits(valid);
        // The small lanes' results counted from their lane bits; then only the lanes that add
        // a bin item (drawn small ones) or go the scalar way are visited, in lane order
        // (submission order), rather than every lane through a branch on its result.
        const uint32_t drawn_bits = small.result_bits[3] & fast;
        stats.zero_area += unsigned(std::popcount(small.result_bits[0] & fast));
        stats.culled_face += unsigned(std::popcount(small.result_bits[1] & fast));
        stats.no_samples += unsigned(std::popcount(small.result_bits[2] & fast));
        stats.setups += unsigned(std::popcount(drawn_bits));
        stats.invalid += unsigned(std::popcount(simd::bits(active) & ~is_valid));
        const uint32_t slow = is_valid & ~fast;
        // Deferring pays when the tile stage finds a bin's triangles near each other in the
        // mesh: here, when consecutive drawn triangles mostly fall into the same tile. Where
        // they scatter over the tiles (a soup), the setups are made now and copied into the
        // bins, which the tile stage then streams.
        bool stored = store_all;
        if (!stored) {
            int drawn = 0, changes = 0;
            int32_t previous = -1;
            for (uint32_t bits = drawn_bits; bits; bits &= bits - 1) {
                const int lane = std::countr_zero(bits);
                const int32_t tile = (small.box[1][lane] >> tile_shift) * tiles_x + (small.box[0][lane] >> tile_shift);
                changes += drawn > 0 && tile != previous;
                previous = tile;
                ++drawn;
            }
            stored = 2 * changes > drawn;
        }
        if (stored) setup_small_triangles(w, inside, options.cull, viewport, options.samples, small);
        for (uint32_t bits = drawn_bits | slow; bits; bits &= bits - 1) {
            const int lane = std::countr_zero(bits);
            const uint32_t id = t + uint32_t(lane);
            if (drawn_bits & (1u << lane)) {
                const BinItem item{id, int16_t(small.box[0][lane]), int16_t(small.box[1][lane]),
                                   int16_t(small.box[2][lane]), int16_t(small.box[3][lane])};
                if (stored) {
                    // Written in place (SmallSetups::write).
                    items.push_back({kStoredSetup | uint32_t(setups.size()), item.minx, item.miny, item.maxx, item.maxy});
                    TriangleSetup& setup = setups.emplace_back();
                    small.write(lane, setup);
                    setup.triangle = id;
                    setup.transparent = transparent(id);
                } else {
                    items.push_back(item);
                }
            } else {
                primitive(v, viewport, options, id, indices[3 * size_t(id)], indices[3 * size_t(id) + 1],
                          indices[3 * size_t(id) + 2], transparent(id), items, setups, stats);
            }
        }
    }
}

}  // namespace tessera::pipeline
