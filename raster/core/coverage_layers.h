// Multisampled visibility as layers that the per-pixel tile passes run on unchanged.
//
// With several samples per pixel, a pixel shows one or more distinct surfaces: triangles, and
// "nothing" (the background, or whatever a compute pass draws there). Shading once per pixel
// per surface, weighted by the samples it covers, is what a hardware MSAA resolve of a
// per-pixel shaded frame computes. Here the distinct surfaces of each pixel are listed and
// dealt out into layers: layer 0 holds every pixel's surface that covers the most samples (the
// first such in sample order), layer j > 0 the pixel's next distinct surfaces in sample order,
// where it has that many. Each layer is an ordinary Tile (triangle id and depth per pixel:
// the nearest depth among the surface's samples) whose `coverage` tells the passes which
// pixels it holds; the passes run on it as on a single-sampled tile, and accumulate() adds
// the layer's colour times its share of the samples into the resolved tile. The colour is
// linear light, so the resolve is too.
//
// A pixel all of whose samples show one surface is one layer-0 entry of weight 1: its
// colour is exactly the single-sample colour of that surface.
//
// A surface that covers only some samples of a pixel may not cover its centre, where the
// passes evaluate it: its plane extrapolated there can sink under its neighbours (a shadow
// ray from that point would find the surface next to it in the way). Given the sample
// positions, a layer also tells, per pixel, where a partly covered surface can be evaluated
// on itself: at its first covered sample ("centroid" evaluation, as D3D's centroid
// interpolation chooses a covered sample for partly covered pixels).
#pragma once
#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

#include "raster/core/aligned_vector.h"
#include "raster/core/tile.h"

namespace tessera {

class CoverageLayers {
public:
    // Lists the surfaces of the pixels of `rect`; sample_at(x, y, s, triangle, depth) reads
    // sample s of frame pixel (x, y). samples in 1 .. 255; `positions`: null, or the samples'
    // offsets from the pixel centre in pixels (for Tile::centroid).
    template <class SampleAt>
    void build(const TileRect& rect, int samples, const glm::vec2* positions, const SampleAt& sample_at);

    int layers() const { return layers_; }
    int samples() const { return samples_; }
    // Pixels with at least one sample covered by a triangle.
    uint64_t covered_pixels() const { return covered_; }

    // Layer j over the rect of the last build(), in this object's buffers (valid until the
    // next layer() or build()): triangle, depth, coverage (samples of the pixel's surface in
    // this layer, 0 where the pixel has none: passes skip it), centroid (with positions)
    // and colour cleared to `clear`; with positions and at most 16 samples, also each
    // pixel's sample mask and the positions (Tile::sample_mask), for passes that sample the
    // pixel's surface themselves.
    Tile layer(int j, const glm::vec4& clear);
    // Adds the colour of the last layer() times coverage / samples into `out` (a tile of the
    // rect's size with `stride` elements per row; layer 0 assigns, the others add).
    void accumulate(int j, glm::vec4* out, size_t stride) const;

private:
    struct Surface {
        uint32_t triangle;
        float depth;
        uint16_t count;
        uint16_t first;  // its first sample
        uint16_t mask;   // its samples, bit s: sample s (the first 16)
    };
    void add_pixel(const Surface* surfaces, int n);

    TileRect rect_;
    int samples_ = 1, layers_ = 0;
    const glm::vec2* positions_ = nullptr;
    uint64_t covered_ = 0;
    std::vector<Surface> surfaces_;  // per pixel in row-major order, its list
    std::vector<uint32_t> first_;    // per pixel, its list's start; one more entry at the end
    AlignedVector<uint32_t> triangle_;
    AlignedVector<float> depth_;
    std::vector<uint8_t> coverage_;
    std::vector<glm::vec4> colour_;
    std::vector<glm::vec2> centroid_;
    std::vector<uint16_t> mask_;
};

template <class SampleAt>
void CoverageLayers::build(const TileRect& rect, int samples, const glm::vec2* positions,
                           const SampleAt& sample_at) {
    rect_ = rect;
    samples_ = samples;
    positions_ = positions;
    layers_ = 0;
    covered_ = 0;
    surfaces_.clear();
    first_.clear();
    Surface list[256];
    for (int y = rect.y0; y < rect.y1; ++y)
        for (int x = rect.x0; x < rect.x1; ++x) {
            int n = 0;
            for (int s = 0; s < samples; ++s) {
                uint32_t triangle;
                float depth;
                sample_at(x, y, s, triangle, depth);
                int k = 0;
                while (k < n && list[k].triangle != triangle) ++k;
                const uint16_t bit = s < 16 ? uint16_t(1u << s) : uint16_t(0);
                if (k == n) list[n++] = {triangle, depth, 1, uint16_t(s), bit};
                else {
                    list[k].depth = depth < list[k].depth ? depth : list[k].depth;
                    ++list[k].count;
                    list[k].mask |= bit;
                }
            }
            add_pixel(list, n);
        }
    first_.push_back(uint32_t(surfaces_.size()));
}

}  // namespace tessera
