#include "raster/pipeline/primitive_stage.h"

#include "raster/pipeline/clip.h"
#include "raster/pipeline/triangle_setup_lanes.h"
#include "raster/simd/lane_math.h"

#include <algorithm>
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

// The scalar path for triangle t with vertex indices i0 i1 i2 (each below the vertex count)
// and the union `codes` of their outcodes: reject, clip, or set up and append.
void primitive(const ClipVertices& v, const Viewport& viewport, const RasterOptions& options, uint32_t t,
               uint32_t i0, uint32_t i1, uint32_t i2, uint8_t transparent, std::vector<TriangleSetup>& out,
               RasterStats& stats) {
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
        // Set up on the stack, copied out only when drawn: most culled triangles then cost
        // no write to `out` (bench_raster BM_Setup/1000: 12.7 -> 12.0 ms).
        const SetupResult result = setup_triangle(v.projected[i0].window, v.projected[i1].window,
                                                  v.projected[i2].window, options.cull, viewport, setup, options.samples);
        count(result, stats);
        if (result == SetupResult::drawn) {
            setup.triangle = t;
            setup.transparent = transparent;
            out.push_back(setup);
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
            out.push_back(setup);
        }
    }
}

}  // namespace

void run_primitive_stage(const Mesh& mesh, const ClipVertices& v, const Viewport& viewport,
                         const RasterOptions& options, uint32_t first, uint32_t last,
                         std::vector<TriangleSetup>& out, RasterStats& stats) {
    using simd::kLanes;
    using simd::vint;
    using simd::vmask;
    const uint32_t* indices = mesh.indices.data();
    const int32_t vertex_count = int32_t(v.size());  // < 2^31 (Rasterizer::render checks)
    const bool any_transparent = !options.transparent.empty();
    const int32_t* records = reinterpret_cast<const int32_t*>(v.projected.data());
    static_assert(sizeof(ProjectedVertex) == 4 * sizeof(int32_t) && offsetof(ProjectedVertex, code) == 12);
    stats.triangles += last - first;
    if (vertex_count == 0) {  // every index is out of range
        stats.invalid += last - first;
        return;
    }
    out.reserve(out.size() + (last - first));
    SmallSetups small;
    // kLanes triangles at a time: those whose corners all lie inside the guard band, and whose
    // vertex box is small, are set up in lanes (triangle_setup_lanes.h); the others, in
    // submission order between them, by the scalar path.
    for (uint32_t t = first; t < last; t += kLanes) {
        const int n = int(std::min<uint32_t>(kLanes, last - t));
        const vmask active = simd::lane_index() < vint(n);
        const vint triangle_offset = simd::select(active, simd::lane_index() * vint(3), vint(0));
        const int32_t* corner_indices = reinterpret_cast<const int32_t*>(indices + 3 * size_t(t));
        vint index[3];
        vmask valid = active;
        for (int k = 0; k < 3; ++k) {
            index[k] = simd::gather_int(corner_indices + k, triangle_offset);
            // Indices of 2^31 and more read as negative: below the count means valid.
            valid = valid & (vint(-1) < index[k]) & (index[k] < vint(vertex_count));
        }
        WindowLanes w;
        vint codes(0);
        for (int k = 0; k < 3; ++k) {
            const vint record = simd::shift_left<2>(simd::select(valid, index[k], vint(0)));
            w.X[k] = simd::gather_int(records, record);
            w.Y[k] = simd::gather_int(records + 1, record);
            w.z[k] = simd::gather(reinterpret_cast<const float*>(records + 2), record);
            codes = codes | simd::gather_int(records + 3, record);
        }
        const vmask inside = valid & (codes == vint(0));
        const uint32_t scalar = simd::bits(setup_small_triangles(w, inside, options.cull, viewport, options.samples, small));
        const uint32_t fast = simd::bits(inside) & ~scalar, is_valid = simd::bits(valid);
        for (int lane = 0; lane < n; ++lane) {
            const uint32_t id = t + uint32_t(lane);
            const uint8_t transparent = any_transparent && options.transparent[id] ? 1 : 0;
            if (fast & (1u << lane)) {
                count(small.result[lane], stats);
                if (small.result[lane] == SetupResult::drawn) {
                    TriangleSetup& setup = out.emplace_back();
                    small.write(lane, setup);
                    setup.triangle = id;
                    setup.transparent = transparent;
                }
            } else if (is_valid & (1u << lane)) {
                primitive(v, viewport, options, id, indices[3 * size_t(id)], indices[3 * size_t(id) + 1],
                          indices[3 * size_t(id) + 2], transparent, out, stats);
            } else {
                ++stats.invalid;
            }
        }
    }
}

}  // namespace tessera::pipeline
