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

    // build() from row-major planes, one per sample: sample s of the rect's pixel p has id
    // triangles[s * area + p] and window depth depths[s * area + p] (area: the rect's pixels).
    void build_planes(const TileRect& rect, int samples, const glm::vec2* positions, const uint32_t* triangles,
                      const float* depths);
    // build() for a rect whose every sample shows `triangle` at window depth `depth`.
    void build_uniform(const TileRect& rect, int samples, const glm::vec2* positions, uint32_t triangle, float depth);

    // After build(): where the layers' Tile::sample_depth reads each sample's depth (see
    // there: `origin` at the rect's first pixel, strides in elements). build_planes() sets it
    // to its planes, build_uniform() to none (every sample has the one depth).
    void set_sample_depths(const float* origin, size_t row, size_t pixel_step, size_t sample_step) {
        sample_depth_ = origin;
        sample_depth_row_ = row;
        sample_depth_pixel_step_ = pixel_step;
        sample_depth_sample_step_ = sample_step;
    }

    int layers() const { return layers_; }
    int samples() const { return samples_; }
    // Pixels with at least one sample covered by a triangle.
    uint64_t covered_pixels() const { return covered_; }

    // Layer j of the pixels the last build() listed, to be resolved into `out` (the rect's
    // colour: `stride` elements per row from its first pixel). Layer 0 covers the rect and
    // its colour is `out` itself, cleared to `clear`; a layer j > 0 covers the part of the
    // rect around the pixels that have a (j+1)-th surface (their bounding box grown by one
    // pixel, within the rect: edge pixels are a small part of most tiles, and the passes need
    // not scan the rest; the extra pixel keeps every neighbour a pass compares inside the
    // tile, see march/silhouette_grid.h), with its colour, cleared to `clear`, in this
    // object's buffers. Valid until the next layer() or build(). It holds triangle, depth,
    // coverage (samples of the pixel's surface in this layer, 0 where the pixel has none:
    // passes skip it), centroid (with positions); with positions and at most 16 samples,
    // also each pixel's sample mask and the positions (Tile::sample_mask), for passes that
    // sample the pixel's surface themselves.
    Tile layer(int j, const glm::vec4& clear, glm::vec4* out, size_t stride);
    // Resolves the last layer() into its `out`: layer 0's colour is scaled by coverage /
    // samples where the pixel is partly covered, the others' colour times coverage / samples
    // is added.
    void accumulate();
    // Layer 0's ids and depths as built (before any pass), row-major over the rect.
    const uint32_t* primary_triangles() const { return primary_triangle_.data(); }
    const float* primary_depths() const { return primary_depth_.data(); }

private:
    struct Surface {
        uint32_t triangle;
        float depth;
        uint16_t count;
        uint16_t first;  // its first sample
        uint16_t mask;   // its samples, bit s: sample s (the first 16)
    };
    // Layer 0 of pixel p (row-major in the rect) is written straight into the arrays layer(0)
    // hands out; the pixel's other surfaces, if any, are listed in `others_`.
    void start(const TileRect& rect, int samples, const glm::vec2* positions);
    void set_primary(size_t p, const Surface& surface);
    // Pixel p whose samples (ids triangle[s * step], depths depth[s * step]) show more than
    // one surface: its surfaces listed, layer 0 the one with the most samples.
    void add_mixed_pixel(size_t p, const uint32_t* triangle, const float* depth, size_t step);
    // The sample mask of a pixel wholly covered by one surface (the first 16 samples).
    static uint16_t all_samples(int samples) {
        return samples >= 16 ? uint16_t(0xFFFF) : uint16_t((1u << samples) - 1u);
    }
    // Where a surface is evaluated (Tile::centroid): the centre when it covers every sample,
    // else its first sample.
    glm::vec2 centroid_of(const Surface& surface) const {
        return int(surface.count) == samples_ ? glm::vec2(0.0f) : positions_[surface.first];
    }
    // The part of the rect layer j > 0 covers (see layer()).
    TileRect layer_rect(int j) const;

    TileRect rect_;
    int samples_ = 1, layers_ = 0;
    const glm::vec2* positions_ = nullptr;
    uint64_t covered_ = 0;
    // Layer 0, one entry per pixel: what most pixels of a tile are, with nothing to look up.
    AlignedVector<uint32_t> primary_triangle_;
    AlignedVector<float> primary_depth_;
    std::vector<uint8_t> primary_coverage_;
    std::vector<glm::vec2> primary_centroid_;
    std::vector<uint16_t> primary_mask_;
    // Layers 1 and up: per pixel in row-major order, its other surfaces in sample order of
    // their first samples; first_[p] .. first_[p + 1] are pixel p's.
    std::vector<Surface> others_;
    std::vector<uint32_t> first_;
    std::vector<uint32_t> mixed_pixels_;  // the pixels with more than one surface, in order
    std::vector<uint8_t> mixed_;  // build_planes: per pixel, whether its samples differ
    // extent_[j - 1]: bounding box of the pixels with a (j+1)-th surface, rect-relative.
    std::vector<TileRect> extent_;
    // Layers 1 and up as layer() hands them out.
    AlignedVector<uint32_t> triangle_;
    AlignedVector<float> depth_;
    std::vector<uint8_t> coverage_;
    std::vector<glm::vec2> centroid_;
    std::vector<uint16_t> mask_;
    std::vector<glm::vec4> colour_;
    const float* sample_depth_ = nullptr;  // set_sample_depths()
    size_t sample_depth_row_ = 0, sample_depth_pixel_step_ = 0, sample_depth_sample_step_ = 0;
    // The last layer(), for accumulate().
    int layer_ = 0;
    TileRect layer_rect_;
    const uint8_t* layer_coverage_ = nullptr;
    glm::vec4* out_ = nullptr;
    size_t out_stride_ = 0;
};

template <class SampleAt>
void CoverageLayers::build(const TileRect& rect, int samples, const glm::vec2* positions,
                           const SampleAt& sample_at) {
    start(rect, samples, positions);
    const uint16_t all = all_samples(samples);
    uint32_t triangle[256];
    float depth[256];
    size_t p = 0;
    for (int y = rect.y0; y < rect.y1; ++y)
        for (int x = rect.x0; x < rect.x1; ++x, ++p) {
            bool one = true;
            for (int s = 0; s < samples; ++s) {
                sample_at(x, y, s, triangle[s], depth[s]);
                one = one && triangle[s] == triangle[0];
            }
            first_.push_back(uint32_t(others_.size()));
            if (one) {  // every sample shows one surface: most pixels
                float nearest = depth[0];
                for (int s = 1; s < samples; ++s) nearest = depth[s] < nearest ? depth[s] : nearest;
                set_primary(p, {triangle[0], nearest, uint16_t(samples), 0, all});
                covered_ += triangle[0] != kNoTriangle;
                continue;
            }
            add_mixed_pixel(p, triangle, depth, 1);
        }
    first_.push_back(uint32_t(others_.size()));
}

}  // namespace tessera
