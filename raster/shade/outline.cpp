#include "raster/shade/outline.h"

#include <algorithm>
#include <cmath>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace tessera::shade {
namespace {

// w = 1 / d from window depth z = z_ndc * 0.5 + 0.5: the inverse of the perspective's z row,
// d = 2 n f / (f + n - z_ndc (f - n)), so w is affine in z (and in screen space on a plane).
struct InverseDistance {
    double n, f;
    float operator()(float z) const {
        const double z_ndc = 2.0 * double(z) - 1.0;
        return float((f + n - z_ndc * (f - n)) / (2.0 * n * f));
    }
};

bool is_background(float depth) { return !(depth < 1.0f); }

}  // namespace

bool any_outlined(std::span<const scene::Material> materials) {
    return std::any_of(materials.begin(), materials.end(),
                       [](const scene::Material& m) { return m.model == scene::ShadingModel::toon; });
}

void draw_outlines(const VisibilityBuffer& visibility, const Camera& camera,
                   std::span<const uint32_t> triangle_material, std::span<const scene::Material> materials,
                   std::vector<glm::vec4>& colour, int row_begin, int row_end) {
    const int w = visibility.width, h = visibility.height;
    row_begin = std::max(row_begin, 0);
    row_end = std::min(row_end, h);
    if (row_begin >= row_end || !any_outlined(materials)) return;
    const InverseDistance inverse{camera.near, camera.far};

    // The material of what pixel i shows; marched surfaces (no triangle) have none.
    constexpr uint32_t kNoMaterial = 0xFFFFFFFFu;
    const auto material_at = [&](size_t i) {
        const uint32_t t = visibility.triangle[i];
        return t < triangle_material.size() ? triangle_material[t] : kNoMaterial;
    };
    // Along one axis through p (material m, inverse distance wp): is p on the near side of an
    // edge? At the frame's border only the neighbour that exists counts, and not for the crease.
    const auto edge = [&](uint32_t m, float wp, int ax, int ay, int bx, int by, bool has_a, bool has_b) {
        float w_side[2] = {wp, wp};
        const int xs[2] = {ax, bx}, ys[2] = {ay, by};
        const bool has[2] = {has_a, has_b};
        for (int k = 0; k < 2; ++k) {
            if (!has[k]) continue;
            const size_t q = size_t(ys[k]) * size_t(w) + size_t(xs[k]);
            if (is_background(visibility.depth[q])) return true;
            w_side[k] = inverse(visibility.depth[q]);
            if (material_at(q) != m && w_side[k] < wp) return true;  // another material behind
        }
        if (!has_a || !has_b) return false;
        const float step = (wp - std::min(w_side[0], w_side[1])) / wp;          // > 0: one lies farther
        const float crease = std::fabs(w_side[0] + w_side[1] - 2.0f * wp) / wp;  // 0 across a plane
        return step > kOutlineStep && crease > kOutlineStep;
    };

    tbb::parallel_for(tbb::blocked_range<int>(row_begin, row_end, 8), [&](const tbb::blocked_range<int>& rows) {
        for (int y = rows.begin(); y < rows.end(); ++y)
            for (int x = 0; x < w; ++x) {
                const size_t i = size_t(y) * size_t(w) + size_t(x);
                const uint32_t t = visibility.triangle[i];
                if (t == kNoTriangle || t >= triangle_material.size()) continue;
                const uint32_t m = triangle_material[t];
                if (m >= materials.size() || materials[m].model != scene::ShadingModel::toon) continue;
                const float wp = inverse(visibility.depth[i]);
                if (!(wp > 0.0f)) continue;
                if (edge(m, wp, x - 1, y, x + 1, y, x > 0, x + 1 < w) || edge(m, wp, x, y - 1, x, y + 1, y > 0, y + 1 < h))
                    colour[i] = glm::vec4(0.0f, 0.0f, 0.0f, colour[i].a);
            }
    });
}

}  // namespace tessera::shade
