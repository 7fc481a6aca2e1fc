#include "raster/pipeline/primitive_stage.h"

#include "raster/pipeline/clip.h"

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
        const ProjectedVertex& p0 = v.projected[i0];
        const ProjectedVertex& p1 = v.projected[i1];
        const ProjectedVertex& p2 = v.projected[i2];
        const uint32_t c0 = p0.code, c1 = p1.code, c2 = p2.code;
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
        TriangleSetup setup;
        if (codes == 0) {
            // Set up on the stack, copied out only when drawn: most culled triangles then cost
            // no write to `out` (bench_raster BM_Setup/1000: 12.7 -> 12.0 ms).
            const SetupResult result =
                setup_triangle(p0.window, p1.window, p2.window, options.cull, viewport, setup, options.samples);
            count(result, stats);
            if (result == SetupResult::drawn) {
                setup.triangle = t;
                setup.transparent = transparent;
                out.push_back(setup);
            }
            continue;
        }
        ++stats.clipped;
        const glm::vec4 in[3] = {v.clip(i0), v.clip(i1), v.clip(i2)};
        glm::vec4 polygon[kMaxClippedVertices];
        const int n = clip_triangle(in, codes, viewport, polygon);
        if (n < 3) continue;  // nothing left inside: counted as clipped
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
}

}  // namespace tessera::pipeline
