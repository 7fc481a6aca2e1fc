#include "raster/core/coverage_layers.h"

#include <algorithm>

#include "raster/core/visibility.h"

namespace tessera {

void CoverageLayers::set_primary(size_t p, const Surface& surface) {
    primary_triangle_[p] = surface.triangle;
    primary_depth_[p] = surface.depth;
    primary_coverage_[p] = uint8_t(surface.count);
    if (positions_)
        primary_centroid_[p] = int(surface.count) == samples_ ? glm::vec2(0.0f) : positions_[surface.first];
    if (positions_ && samples_ <= 16) primary_mask_[p] = surface.mask;
}

void CoverageLayers::add_mixed_pixel(size_t p, const uint32_t* triangle, const float* depth, size_t step) {
    Surface list[256];
    int n = 0;
    for (int s = 0; s < samples_; ++s) {
        const uint32_t t = triangle[size_t(s) * step];
        const float d = depth[size_t(s) * step];
        int k = 0;
        while (k < n && list[k].triangle != t) ++k;
        const uint16_t bit = s < 16 ? uint16_t(1u << s) : uint16_t(0);
        if (k == n) list[n++] = {t, d, 1, uint16_t(s), bit};
        else {
            list[k].depth = d < list[k].depth ? d : list[k].depth;
            ++list[k].count;
            list[k].mask |= bit;
        }
    }
    // Layer 0: the surface with the most samples, the first of them in sample order.
    int best = 0;
    for (int k = 1; k < n; ++k)
        if (list[k].count > list[best].count) best = k;
    set_primary(p, list[best]);
    for (int k = 0; k < n; ++k)
        if (k != best) others_.push_back(list[k]);
    layers_ = std::max(layers_, n);
    covered_ += n > 1 || list[0].triangle != kNoTriangle;
}

void CoverageLayers::start(const TileRect& rect, int samples, const glm::vec2* positions) {
    rect_ = rect;
    samples_ = samples;
    positions_ = positions;
    covered_ = 0;
    const size_t area = size_t(rect.width()) * size_t(rect.height());
    layers_ = area ? 1 : 0;
    primary_triangle_.resize(area);
    primary_depth_.resize(area);
    primary_coverage_.resize(area);
    if (positions) primary_centroid_.resize(area);
    if (positions && samples <= 16) primary_mask_.resize(area);
    others_.clear();
    first_.clear();
    sample_depth_ = nullptr;
}

void CoverageLayers::build_planes(const TileRect& rect, int samples, const glm::vec2* positions,
                                  const uint32_t* triangles, const float* depths) {
    start(rect, samples, positions);
    const size_t area = size_t(rect.width()) * size_t(rect.height());
    // Layer 0 as though every pixel showed one surface (sample 0's, at its samples' nearest
    // depth, taken in sample order as build() takes it), in loops over whole planes that the
    // compiler vectorises; then the pixels whose samples differ are listed one by one.
    uint32_t* t0 = primary_triangle_.data();
    float* d0 = primary_depth_.data();
    std::copy_n(triangles, area, t0);
    std::copy_n(depths, area, d0);
    mixed_.assign(area, 0);
    for (int s = 1; s < samples; ++s) {
        const uint32_t* t = triangles + size_t(s) * area;
        const float* d = depths + size_t(s) * area;
        uint8_t* m = mixed_.data();
        for (size_t p = 0; p < area; ++p) {
            d0[p] = d[p] < d0[p] ? d[p] : d0[p];
            m[p] |= uint8_t(t[p] != t0[p]);
        }
    }
    std::fill_n(primary_coverage_.data(), area, uint8_t(samples));
    if (positions) std::fill_n(primary_centroid_.data(), area, glm::vec2(0.0f));
    if (positions && samples <= 16)
        std::fill_n(primary_mask_.data(), area, samples >= 16 ? uint16_t(0xFFFF) : uint16_t((1u << samples) - 1u));
    first_.resize(area + 1);
    for (size_t p = 0; p < area; ++p) {
        first_[p] = uint32_t(others_.size());
        if (!mixed_[p]) covered_ += t0[p] != kNoTriangle;
        else add_mixed_pixel(p, triangles + p, depths + p, area);
    }
    first_[area] = uint32_t(others_.size());
    set_sample_depths(depths, size_t(rect.width()), 1, area);
}

void CoverageLayers::build_uniform(const TileRect& rect, int samples, const glm::vec2* positions, uint32_t triangle,
                                   float depth) {
    rect_ = rect;
    samples_ = samples;
    positions_ = positions;
    const size_t area = size_t(rect.width()) * size_t(rect.height());
    layers_ = area ? 1 : 0;
    covered_ = triangle != kNoTriangle ? area : 0;
    primary_triangle_.assign(area, triangle);
    primary_depth_.assign(area, depth);
    primary_coverage_.assign(area, uint8_t(samples));
    if (positions) primary_centroid_.assign(area, glm::vec2(0.0f));
    if (positions && samples <= 16)
        primary_mask_.assign(area, samples >= 16 ? uint16_t(0xFFFF) : uint16_t((1u << samples) - 1u));
    others_.clear();
    first_.assign(area + 1, 0);
    sample_depth_ = nullptr;
}

Tile CoverageLayers::layer(int j, const glm::vec4& clear) {
    const size_t w = size_t(rect_.width()), area = w * size_t(rect_.height());
    const bool masks = positions_ && samples_ <= 16;
    colour_.assign(area, clear);
    Tile tile;
    tile.rect = rect_;
    tile.stride = w;
    tile.colour = colour_.data();
    tile.colour_stride = w;
    if (j == 0) {
        // Handed out as built: passes may change the ids and depths (a marched surface in
        // front), which matters to nothing after them but the resolve of this layer.
        tile.triangle = primary_triangle_.data();
        tile.depth = primary_depth_.data();
        tile.coverage = layer_coverage_ = primary_coverage_.data();
        tile.centroid = positions_ ? primary_centroid_.data() : nullptr;
        if (masks) tile.sample_mask = primary_mask_.data();
    } else {
        triangle_.resize(area);
        depth_.resize(area);
        coverage_.resize(area);
        if (positions_) centroid_.resize(area);
        if (masks) mask_.resize(area);
        for (size_t p = 0; p < area; ++p) {
            const uint32_t at = first_[p] + uint32_t(j - 1);
            if (at < first_[p + 1]) {
                const Surface& s = others_[at];
                triangle_[p] = s.triangle;
                depth_[p] = s.depth;
                coverage_[p] = uint8_t(s.count);
                if (positions_)
                    centroid_[p] = int(s.count) == samples_ ? glm::vec2(0.0f) : positions_[s.first];
                if (masks) mask_[p] = s.mask;
            } else {
                // Nothing here: no triangle, and a depth nearer than anything, so that passes
                // which test depth (transparency, marching, fog) find nothing to do either.
                triangle_[p] = kNoTriangle;
                depth_[p] = 0.0f;
                coverage_[p] = 0;
                if (masks) mask_[p] = 0;
            }
        }
        tile.triangle = triangle_.data();
        tile.depth = depth_.data();
        tile.coverage = layer_coverage_ = coverage_.data();
        tile.centroid = positions_ ? centroid_.data() : nullptr;
        if (masks) tile.sample_mask = mask_.data();
    }
    if (masks) {
        tile.sample_count = samples_;
        tile.sample_offsets = positions_;
        tile.sample_depth = sample_depth_;
        tile.sample_depth_row = sample_depth_row_;
        tile.sample_depth_pixel_step = sample_depth_pixel_step_;
        tile.sample_depth_sample_step = sample_depth_sample_step_;
    }
    return tile;
}

void CoverageLayers::copy_primary(uint32_t* triangle, float* depth, size_t stride) const {
    const size_t w = size_t(rect_.width());
    for (size_t y = 0; y < size_t(rect_.height()); ++y) {
        std::copy_n(primary_triangle_.data() + y * w, w, triangle + y * stride);
        std::copy_n(primary_depth_.data() + y * w, w, depth + y * stride);
    }
}

void CoverageLayers::accumulate(int j, glm::vec4* out, size_t stride) const {
    const size_t w = size_t(rect_.width());
    const float share = 1.0f / float(samples_);
    for (int y = 0; y < rect_.height(); ++y)
        for (size_t x = 0; x < w; ++x) {
            const size_t p = size_t(y) * w + x;
            if (!layer_coverage_[p]) continue;
            const glm::vec4 c = colour_[p] * (float(layer_coverage_[p]) * share);
            glm::vec4& o = out[size_t(y) * stride + x];
            o = j == 0 ? c : o + c;
        }
}

}  // namespace tessera
