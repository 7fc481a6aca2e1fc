#include "raster/primitive_stage.h"

#include "raster/clip.h"

namespace tessera {

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

void run_primitive_stage(const Mesh& mesh, const ClipVertices& v, const Viewport& viewport,
                         const RasterOptions& options, uint32_t first, uint32_t last,
                         std::vector<TriangleSetup>& out, RasterStats& stats) {
    const uint32_t* indices = mesh.indices.data();
    const size_t vertex_count = v.size();
    const bool any_transparent = !options.transparent.empty();
    stats.triangles += last - first;
    for (uint32_t t = first; t < last; ++t) {
        const uint32_t i0 = indices[3 * size_t(t)], i1 = indices[3 * size_t(t) + 1], i2 = indices[3 * size_t(t) + 2];
        if (i0 >= vertex_count || i1 >= vertex_count || i2 >= vertex_count) {
            ++stats.invalid;
            continue;
        }
        const uint32_t c0 = v.code[i0], c1 = v.code[i1], c2 = v.code[i2];
        const uint32_t codes = c0 | c1 | c2;
        if (codes & kClipInvalid) {
            ++stats.invalid;
            continue;
        }
        if (c0 & c1 & c2) {
            ++stats.outside;
            continue;
        }
        const uint8_t transparent = any_transparent && options.transparent[t] ? 1 : 0;
        if (codes == 0) {
            // Set up in place; dropped again when not drawn.
            TriangleSetup& setup = out.emplace_back();
            const SetupResult result = setup_triangle({v.X[i0], v.Y[i0], v.Z[i0]}, {v.X[i1], v.Y[i1], v.Z[i1]},
                                                      {v.X[i2], v.Y[i2], v.Z[i2]}, options.cull, viewport, setup);
            count(result, stats);
            if (result == SetupResult::drawn) {
                setup.triangle = t;
                setup.transparent = transparent;
            } else {
                out.pop_back();
            }
            continue;
        }
        TriangleSetup setup;
        ++stats.clipped;
        const glm::vec4 in[3] = {v.clip(i0), v.clip(i1), v.clip(i2)};
        glm::vec4 polygon[kMaxClippedVertices];
        const int n = clip_triangle(in, codes, viewport, polygon);
        if (n < 3) continue;  // nothing left inside: counted as clipped
        WindowVertex w[kMaxClippedVertices];
        for (int i = 0; i < n; ++i) w[i] = project_and_snap(viewport, polygon[i]);
        // The clipped polygon is convex: a fan from its first vertex keeps the winding.
        for (int i = 1; i + 1 < n; ++i) {
            const SetupResult result = setup_triangle(w[0], w[i], w[i + 1], options.cull, viewport, setup);
            count(result, stats);
            if (result == SetupResult::drawn) {
                setup.triangle = t;
                setup.transparent = transparent;
                out.push_back(setup);
            }
        }
    }
}

}  // namespace tessera
