// The visibility buffer: per pixel, the id of the nearest triangle and its window depth.
// Both renderers fill it (the tile rasterizer, and Embree's primary rays), and shading reads
// only it and the mesh, so the two are shaded by the same code on identical inputs.
#pragma once
#include <cstdint>
#include <vector>

#include "raster/core/aligned_vector.h"

namespace tessera {

inline constexpr uint32_t kNoTriangle = 0xFFFFFFFFu;

struct VisibilityBuffer {
    int width = 0;
    int height = 0;
    // Cache-line aligned, so that rows whose width is a multiple of 16 start on a line: the
    // rasterizer then streams whole lines into them (TileBuffers::flush).
    AlignedVector<uint32_t> triangle;  // rows top to bottom; kNoTriangle where nothing covers
    AlignedVector<float> depth;        // window depth z_ndc * 0.5 + 0.5; 1.0 where empty
    // Multisampled renders (samples > 1) fill triangle and depth with each pixel's main
    // surface (the one covering most samples, coverage_layers.h) and, when asked to keep
    // them, these with every sample: pixel-major, sample s of pixel (x, y) at
    // (y * width + x) * samples + s. Empty otherwise.
    int samples = 1;
    AlignedVector<uint32_t> sample_triangle;
    AlignedVector<float> sample_depth;

    void reset(int w, int h) {
        width = w;
        height = h;
        triangle.assign(size_t(w) * size_t(h), kNoTriangle);
        depth.assign(size_t(w) * size_t(h), 1.0f);
        samples = 1;
        sample_triangle.clear();
        sample_depth.clear();
    }

    size_t sample_index(int x, int y, int s) const {
        return (size_t(y) * size_t(width) + size_t(x)) * size_t(samples) + size_t(s);
    }
};

}  // namespace tessera
