#include "raster/core/coverage_layers.h"

#include <algorithm>
#include <cstring>

#include "raster/core/visibility.h"

namespace tessera {

void CoverageLayers::set_primary(size_t p, const Surface& surface) {
    primary_triangle_[p] = surface.triangle;
    primary_depth_[p] = surface.depth;
    primary_coverage_[p] = uint8_t(surface.count);
    if (positions_) primary_centroid_[p] = centroid_of(surface);
    if (positions_ && samples_ <= 16) primary_mask_[p] = surface.mask;
}

void CoverageLayers::add_mixed_pixel(size_t p, const uint32_t* triangle, const float* depth, size_t step) {
    Surface list[256];
    list[0] = {triangle[0], depth[0], 1, 0, 1};  // sample 0 starts the list
    int n = 1;
    for (int s = 1; s < samples_; ++s) {
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
    if (n > 1) mixed_pixels_.push_back(uint32_t(p));
    const int w = rect_.width(), x = int(p % size_t(w)), y = int(p / size_t(w));
    for (int j = 1; j < n; ++j) {
        if (extent_.size() < size_t(j)) extent_.push_back({x, y, x + 1, y + 1});
        TileRect& e = extent_[size_t(j - 1)];
        e = {std::min(e.x0, x), std::min(e.y0, y), std::max(e.x1, x + 1), std::max(e.y1, y + 1)};
    }
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
    extent_.clear();
    mixed_pixels_.clear();
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
        std::fill_n(primary_mask_.data(), area, all_samples(samples));
    const uint8_t* m = mixed_.data();
    uint64_t covered = 0;
    for (size_t p = 0; p < area; ++p) covered += !m[p] & (t0[p] != kNoTriangle);
    covered_ = covered;
    // Runs of pixels that show one surface (memchr finds the next mixed one a vector at a
    // time) share the same start in others_.
    first_.resize(area + 1);
    for (size_t p = 0;;) {
        const void* hit = std::memchr(m + p, 1, area - p);
        const size_t next = hit ? size_t(static_cast<const uint8_t*>(hit) - m) : area;
        std::fill(first_.begin() + std::ptrdiff_t(p), first_.begin() + std::ptrdiff_t(next), uint32_t(others_.size()));
        if (next == area) break;
        first_[next] = uint32_t(others_.size());
        add_mixed_pixel(next, triangles + next, depths + next, area);
        p = next + 1;
    }
    first_[area] = uint32_t(others_.size());
    set_sample_depths(depths, size_t(rect.width()), 1, area);
}

void CoverageLayers::build_uniform(const TileRect& rect, int samples, const glm::vec2* positions, uint32_t triangle,
                                   float depth) {
    start(rect, samples, positions);
    const size_t area = size_t(rect.width()) * size_t(rect.height());
    covered_ = triangle != kNoTriangle ? area : 0;
    std::fill_n(primary_triangle_.data(), area, triangle);
    std::fill_n(primary_depth_.data(), area, depth);
    std::fill_n(primary_coverage_.data(), area, uint8_t(samples));
    if (positions) std::fill_n(primary_centroid_.data(), area, glm::vec2(0.0f));
    if (positions && samples <= 16) std::fill_n(primary_mask_.data(), area, all_samples(samples));
    first_.assign(area + 1, 0);
}

TileRect CoverageLayers::layer_rect(int j) const {
    const TileRect& e = extent_[size_t(j - 1)];
    return {rect_.x0 + std::max(e.x0 - 1, 0), rect_.y0 + std::max(e.y0 - 1, 0),
            rect_.x0 + std::min(e.x1 + 1, rect_.width()), rect_.y0 + std::min(e.y1 + 1, rect_.height())};
}

Tile CoverageLayers::layer(int j, const glm::vec4& clear, glm::vec4* out, size_t stride) {
    const bool masks = positions_ && samples_ <= 16;
    layer_ = j;
    layer_rect_ = j == 0 ? rect_ : layer_rect(j);
    out_ = out;
    out_stride_ = stride;
    const size_t w = size_t(layer_rect_.width()), area = w * size_t(layer_rect_.height());
    Tile tile;
    tile.rect = layer_rect_;
    tile.stride = w;
    if (j == 0) {
        for (size_t y = 0; y < size_t(layer_rect_.height()); ++y) std::fill_n(out + y * stride, w, clear);
        tile.colour = out;
        tile.colour_stride = stride;
        // Handed out as built: passes may change the ids and depths (a marched surface in
        // front), which matters to nothing after them but the resolve of this layer.
        tile.triangle = primary_triangle_.data();
        tile.depth = primary_depth_.data();
        tile.coverage = layer_coverage_ = primary_coverage_.data();
        tile.centroid = positions_ ? primary_centroid_.data() : nullptr;
        if (masks) tile.sample_mask = primary_mask_.data();
    } else {
        colour_.assign(area, clear);
        tile.colour = colour_.data();
        tile.colour_stride = w;
        triangle_.resize(area);
        depth_.resize(area);
        coverage_.resize(area);
        if (positions_) centroid_.resize(area);
        if (masks) mask_.resize(area);
        // Nothing where the pixel has no (j+1)-th surface: no triangle, and a depth nearer
        // than anything, so that passes which test depth (transparency, marching, fog) find
        // nothing to do either. Then the pixels that have one, from the list of mixed ones.
        std::fill_n(triangle_.data(), area, kNoTriangle);
        std::fill_n(depth_.data(), area, 0.0f);
        std::fill_n(coverage_.data(), area, uint8_t(0));
        if (masks) std::fill_n(mask_.data(), area, uint16_t(0));
        const size_t rect_w = size_t(rect_.width());
        const size_t dx = size_t(layer_rect_.x0 - rect_.x0), dy = size_t(layer_rect_.y0 - rect_.y0);
        for (const uint32_t p : mixed_pixels_) {
            const uint32_t at = first_[p] + uint32_t(j - 1);
            if (at >= first_[p + 1]) continue;
            const size_t q = (size_t(p) / rect_w - dy) * w + (size_t(p) % rect_w - dx);
            const Surface& s = others_[at];
            triangle_[q] = s.triangle;
            depth_[q] = s.depth;
            coverage_[q] = uint8_t(s.count);
            if (positions_) centroid_[q] = centroid_of(s);
            if (masks) mask_[q] = s.mask;
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
        // Addressed from the layer's first pixel, which for j > 0 may lie inside the rect.
        tile.sample_depth = sample_depth_ ? sample_depth_ + size_t(layer_rect_.y0 - rect_.y0) * sample_depth_row_ +
                                                size_t(layer_rect_.x0 - rect_.x0) * sample_depth_pixel_step_
                                          : nullptr;
        tile.sample_depth_row = sample_depth_row_;
        tile.sample_depth_pixel_step = sample_depth_pixel_step_;
        tile.sample_depth_sample_step = sample_depth_sample_step_;
    }
    return tile;
}

void CoverageLayers::accumulate() {
    const TileRect& r = layer_rect_;
    const size_t w = size_t(r.width());
    const float share = 1.0f / float(samples_);
    glm::vec4* out = out_ + size_t(r.y0 - rect_.y0) * out_stride_ + size_t(r.x0 - rect_.x0);
    // Layer 0's colour is already in `out`; a pixel whose weight is exactly 1 (wholly
    // covered, with a power-of-two sample count) keeps it. A layer j > 0 adds where it holds
    // a surface. The pixels left alone (most of layer 0, most of the others' rects) are
    // skipped eight coverage bytes at a time.
    const bool can_skip = layer_ != 0 || float(samples_) * share == 1.0f;
    const uint8_t skip = layer_ == 0 ? uint8_t(samples_) : uint8_t(0);  // the coverage left alone
    const uint64_t skip_word = uint64_t(skip) * 0x0101010101010101ull;
    for (size_t y = 0; y < size_t(r.height()); ++y) {
        const uint8_t* coverage = layer_coverage_ + y * w;
        const glm::vec4* colour = layer_ == 0 ? nullptr : colour_.data() + y * w;
        glm::vec4* o = out + y * out_stride_;
        for (size_t x = 0; x < w;) {
            if (can_skip && x + 8 <= w) {
                uint64_t word;
                std::memcpy(&word, coverage + x, sizeof(word));
                if (word == skip_word) {
                    x += 8;
                    continue;
                }
            }
            const size_t end = std::min(w, x + 8);
            for (; x < end; ++x) {
                if (can_skip && coverage[x] == skip) continue;
                const float weight = float(coverage[x]) * share;
                o[x] = layer_ == 0 ? o[x] * weight : o[x] + colour[x] * weight;
            }
        }
    }
}

}  // namespace tessera
