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

    void reset(int w, int h) {
        width = w;
        height = h;
        triangle.assign(size_t(w) * size_t(h), kNoTriangle);
        depth.assign(size_t(w) * size_t(h), 1.0f);
    }
};

}  // namespace tessera
