#include "raster/core/coverage_layers.h"

#include <algorithm>

#include "raster/core/visibility.h"

namespace tessera {

void CoverageLayers::add_pixel(const Surface* list, int n) {
    // Layer 0: the surface with the most samples, the first of them in sample order.
    int best = 0;
    for (int k = 1; k < n; ++k)
        if (list[k].count > list[best].count) best = k;
    first_.push_back(uint32_t(surfaces_.size()));
    surfaces_.push_back(list[best]);
    for (int k = 0; k < n; ++k)
        if (k != best) surfaces_.push_back(list[k]);
    layers_ = std::max(layers_, n);
    covered_ += n > 1 || list[0].triangle != kNoTriangle;
}

Tile CoverageLayers::layer(int j, const glm::vec4& clear) {
    const size_t w = size_t(rect_.width()), area = w * size_t(rect_.height());
    triangle_.resize(area);
    depth_.resize(area);
    coverage_.resize(area);
    colour_.assign(area, clear);
    const bool masks = positions_ && samples_ <= 16;
    if (positions_) centroid_.resize(area);
    if (masks) mask_.resize(area);
    for (size_t p = 0; p < area; ++p) {
        const uint32_t at = first_[p] + uint32_t(j);
        if (at < first_[p + 1]) {
            triangle_[p] = surfaces_[at].triangle;
            depth_[p] = surfaces_[at].depth;
            coverage_[p] = uint8_t(surfaces_[at].count);
            if (positions_)
                centroid_[p] = int(surfaces_[at].count) == samples_ ? glm::vec2(0.0f) : positions_[surfaces_[at].first];
            if (masks) mask_[p] = surfaces_[at].mask;
        } else {
            // Nothing here: no triangle, and a depth nearer than anything, so that passes
            // which test depth (transparency, marching, fog) find nothing to do either.
            triangle_[p] = kNoTriangle;
            depth_[p] = 0.0f;
            coverage_[p] = 0;
            if (masks) mask_[p] = 0;
        }
    }
    Tile tile;
    tile.rect = rect_;
    tile.triangle = triangle_.data();
    tile.depth = depth_.data();
    tile.stride = w;
    tile.colour = colour_.data();
    tile.colour_stride = w;
    tile.coverage = coverage_.data();
    tile.centroid = positions_ ? centroid_.data() : nullptr;
    if (masks) {
        tile.sample_mask = mask_.data();
        tile.sample_count = samples_;
        tile.sample_offsets = positions_;
    }
    return tile;
}

void CoverageLayers::accumulate(int j, glm::vec4* out, size_t stride) const {
    const size_t w = size_t(rect_.width());
    const float share = 1.0f / float(samples_);
    for (int y = 0; y < rect_.height(); ++y)
        for (size_t x = 0; x < w; ++x) {
            const size_t p = size_t(y) * w + x;
            if (!coverage_[p]) continue;
            const glm::vec4 c = colour_[p] * (float(coverage_[p]) * share);
            glm::vec4& o = out[size_t(y) * stride + x];
            o = j == 0 ? c : o + c;
        }
}

}  // namespace tessera
