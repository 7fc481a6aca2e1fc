#include "raster/pipeline/reference_rasterizer.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "raster/core/coverage_layers.h"
#include "raster/pipeline/clip.h"
#include "raster/pipeline/sample_pattern.h"
#include "raster/pipeline/triangle_setup.h"
#include "raster/pipeline/vertex_stage.h"

namespace tessera::pipeline {

namespace {

// The D3D coverage rule evaluated directly at pixel centre (px, py) in sub-pixels; `e` gets
// the three edge functions.
bool covers(const WindowVertex v[3], int64_t px, int64_t py, int64_t e[3]) {
    for (int i = 0; i < 3; ++i) {
        const WindowVertex& a = v[i];
        const WindowVertex& b = v[(i + 1) % 3];
        const int64_t dX = b.X - a.X, dY = b.Y - a.Y;
        e[i] = dX * (py - a.Y) - dY * (px - a.X);
        if (e[i] < 0 || (e[i] == 0 && !is_top_left(int32_t(dX), int32_t(dY)))) return false;
    }
    return true;
}

// The depth offset (triangle_setup.h) at the covered sample (fx, fy) pixels from the plane's
// anchor: the plane, plus the edge step of each edge the sample lies exactly on (e == 0).
float offset_at(const DepthPlane& plane, const WindowVertex v[3], float fx, float fy, const int64_t e[3]) {
    float z = std::fma(plane.a, fx, std::fma(plane.b, fy, plane.c));
    for (int i = 0; i < 3; ++i)
        if (e[i] == 0) z = z + plane.edge_step(v[(i + 1) % 3].X - v[i].X, v[(i + 1) % 3].Y - v[i].Y);
    return std::min(std::max(z, -1.0f), 0.0f);
}

// offsets: the depth offsets the test compares, per pixel (and sample), 0 where empty.
void draw(const WindowVertex& v0, const WindowVertex& v1, const WindowVertex& v2, uint32_t id,
          const Viewport& viewport, CullMode cull, std::span<const SampleOffset> pattern, VisibilityBuffer& out,
          std::vector<float>& offsets) {
    const int64_t area2 = int64_t(v1.X - v0.X) * (v2.Y - v0.Y) - int64_t(v1.Y - v0.Y) * (v2.X - v0.X);
    if (area2 == 0) return;
    const bool front = area2 < 0;  // counter-clockwise in NDC (y up) is clockwise on screen
    if ((cull == CullMode::back && !front) || (cull == CullMode::front && front)) return;
    // Orient so that the inside is where every edge function is positive.
    const WindowVertex v[3] = {v0, area2 > 0 ? v1 : v2, area2 > 0 ? v2 : v1};
    const DepthPlane plane = DepthPlane::from(v0, v1, v2);
    // Whole viewport, restricted to the vertices' box only to keep the tests fast.
    const int64_t xmin = std::min({v0.X, v1.X, v2.X}) / kSubpixels - 1;
    const int64_t xmax = std::max({v0.X, v1.X, v2.X}) / kSubpixels + 1;
    const int64_t ymin = std::min({v0.Y, v1.Y, v2.Y}) / kSubpixels - 1;
    const int64_t ymax = std::max({v0.Y, v1.Y, v2.Y}) / kSubpixels + 1;
    for (int64_t y = std::max<int64_t>(ymin, 0); y <= std::min<int64_t>(ymax, viewport.height - 1); ++y)
        for (int64_t x = std::max<int64_t>(xmin, 0); x <= std::min<int64_t>(xmax, viewport.width - 1); ++x) {
            int64_t e[3];
            if (pattern.size() == 1) {
                if (!covers(v, x * kSubpixels + kSubpixels / 2, y * kSubpixels + kSubpixels / 2, e)) continue;
                const float z = offset_at(plane, v, float(int(x) - plane.ax), float(int(y) - plane.ay), e);
                const size_t i = size_t(y) * viewport.width + size_t(x);
                if (z < offsets[i]) {
                    offsets[i] = z;
                    out.depth[i] = window_depth(z);
                    out.triangle[i] = id;
                }
                continue;
            }
            // Multisampled: the same rule at each sample position, 16 sub-pixels per 1/16.
            for (size_t s = 0; s < pattern.size(); ++s) {
                const int64_t px = x * kSubpixels + kSubpixels / 2 + 16 * pattern[s].x;
                const int64_t py = y * kSubpixels + kSubpixels / 2 + 16 * pattern[s].y;
                if (!covers(v, px, py, e)) continue;
                const float fx = float(int(x) - plane.ax) + float(pattern[s].x) * (1.0f / 16.0f);
                const float fy = float(int(y) - plane.ay) + float(pattern[s].y) * (1.0f / 16.0f);
                const float z = offset_at(plane, v, fx, fy, e);
                const size_t i = out.sample_index(int(x), int(y), int(s));
                if (z < offsets[i]) {
                    offsets[i] = z;
                    out.sample_depth[i] = window_depth(z);
                    out.sample_triangle[i] = id;
                }
            }
        }
}

}  // namespace

void reference_rasterize(const Mesh& mesh, const glm::mat4& vp, const Viewport& viewport,
                         const RasterOptions& options, VisibilityBuffer& out) {
    const std::span<const SampleOffset> pattern = sample_pattern(options.samples);
    out.reset(viewport.width, viewport.height);
    if (options.samples > 1) {
        out.samples = options.samples;
        out.sample_triangle.assign(out.triangle.size() * size_t(options.samples), kNoTriangle);
        out.sample_depth.assign(out.depth.size() * size_t(options.samples), 1.0f);
    }
    std::vector<float> offsets(out.depth.size() * size_t(options.samples), 0.0f);
    for (size_t t = 0; t < mesh.triangle_count(); ++t) {
        if (!options.transparent.empty() && options.transparent[t]) continue;
        glm::vec4 clip[3];
        uint32_t codes[3];
        bool valid = true;
        for (int k = 0; k < 3; ++k) {
            const uint32_t index = mesh.indices[3 * t + k];
            if (index >= mesh.vertex_count()) {
                valid = false;
                break;
            }
            const glm::vec3 p = mesh.positions[index];
            clip_position(vp, p.x, p.y, p.z, clip[k].x, clip[k].y, clip[k].z, clip[k].w);
            codes[k] = clip_code(viewport, clip[k].x, clip[k].y, clip[k].z, clip[k].w);
        }
        if (!valid || ((codes[0] | codes[1] | codes[2]) & kClipInvalid) || (codes[0] & codes[1] & codes[2]))
            continue;
        glm::vec4 polygon[kMaxClippedVertices];
        const int n = (codes[0] | codes[1] | codes[2])
                          ? clip_triangle(clip, codes[0] | codes[1] | codes[2], viewport, polygon)
                          : (std::copy(clip, clip + 3, polygon), 3);
        WindowVertex w[kMaxClippedVertices];
        for (int i = 0; i < n; ++i) w[i] = project_and_snap(viewport, polygon[i]);
        for (int i = 1; i + 1 < n; ++i) draw(w[0], w[i], w[i + 1], uint32_t(t), viewport, options.cull, pattern, out, offsets);
    }
    if (options.samples == 1) return;
    // Each pixel's main surface, as the tile rasterizer reports it.
    CoverageLayers layers;
    layers.build(TileRect{0, 0, viewport.width, viewport.height}, options.samples, nullptr,
                 [&](int x, int y, int s, uint32_t& triangle, float& depth) {
                     triangle = out.sample_triangle[out.sample_index(x, y, s)];
                     depth = out.sample_depth[out.sample_index(x, y, s)];
                 });
    const size_t area = size_t(viewport.width) * size_t(viewport.height);
    std::copy_n(layers.primary_triangles(), area, out.triangle.data());
    std::copy_n(layers.primary_depths(), area, out.depth.data());
}

}  // namespace tessera::pipeline
