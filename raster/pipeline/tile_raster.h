// The tile stage's inner loop: one triangle setup against one screen tile (README "One frame,
// as data flows", step 4). Traversal descends tile -> 16x16 block -> SIMD stamp (simd.h: 4x4
// pixels for 16 lanes) with trivial reject / accept on the edge functions, steps the edge
// functions incrementally in int32 lanes (ranges in fixed_point.h) and evaluates the depth
// plane per stamp. Small triangles skip the block level (llvmpipe-style size classes).
#pragma once
#include <cstdint>

#include "raster/core/aligned_vector.h"
#include "raster/core/tile.h"
#include "raster/simd/simd.h"
#include "raster/pipeline/sample_pattern.h"
#include "raster/pipeline/triangle_setup.h"

namespace tessera::pipeline {

// A tile's depth and triangle ids, small enough to stay in L1/L2 while every triangle of the
// tile is drawn. Stamp-swizzled: the kLanes pixels of one stamp are contiguous (one aligned
// vector), stamps in row-major order. Multisampled (samples > 1, sample_pattern.h): one such
// plane per sample, sample s at s * plane(). Depth is held as the depth offset z - 1 that the
// test compares (triangle_setup.h; window_depth() turns it back), 0 where nothing was drawn.
struct TileBuffers {
    int size = 0;
    int samples = 1;
    AlignedVector<float> depth;  // depth offsets
    AlignedVector<uint32_t> triangle;
    AlignedVector<uint32_t> rows;  // flush(): kStampH rows of the tile in row-major order

    void clear(int tile_size, int sample_count = 1);  // depth offset 0 (window depth 1), no triangle
    size_t plane() const { return size_t(size) * size_t(size); }
    // Copies the tile's pixels [0, width) x [0, height) to row-major triangle / window depth arrays
    // with `stride` elements per row (pointing at the tile's first pixel; triangle_out null:
    // depth only, the ids were not written), and leaves the
    // buffers cleared for the next tile of the same size. `stream`: with non-temporal stores
    // (simd::stream_copy) where the rows start on cache lines, for output that is not read
    // again soon; they skip reading each destination line first, which is most of the
    // copy's cost once the frame is out of cache. Single-sampled buffers only.
    void flush(int width, int height, uint32_t* triangle_out, float* depth_out, size_t stride,
               bool stream);
    // Multisampled buffers: every sample's plane to row-major planes of width x height values
    // (plane s at s * width * height; depth as window depth), leaving the buffers cleared.
    void flush_planes(int width, int height, uint32_t* triangle_out, float* depth_out);
    // How many of the tile's pixels [0, width) x [0, height) hold a triangle.
    uint64_t covered_pixels(int width, int height) const;
    // Index of tile-local pixel (x, y) in the arrays.
    size_t index(int x, int y) const {
        const int stamp = (y / simd::kStampH) * (size / simd::kStampW) + x / simd::kStampW;
        return size_t(stamp) * simd::kLanes + (y % simd::kStampH) * simd::kStampW + x % simd::kStampW;
    }
};

// Depth test LESS and write of one opaque triangle into the tile (per sample when the buffers
// are multisampled: coverage and depth at each sample position with the same fill rule).
void rasterize_opaque(const TriangleSetup& t, const TileRect& tile, TileBuffers& buffers);
// The same without triangle ids (depth-only renders: shadow maps).
void rasterize_depth(const TriangleSetup& t, const TileRect& tile, TileBuffers& buffers);

// A covered pixel of a triangle: frame pixel (x, y), its window depth, and the samples it
// covers and passes the depth test at. One sample: the pixel centre, its depth there, mask 1.
// Multisampled (rasterize_tested_samples): the samples of the pixel, bit s for sample s, and
// the nearest of their depths.
struct Fragment {
    uint16_t x, y;
    float depth;
    uint16_t mask = 1;
};

// Appends the fragments of `t` inside `tile` whose depth is LESS than depth[(y - y0) * stride +
// (x - x0)] to `out` (nothing is written to depth); returns how many were appended.
size_t rasterize_tested(const TriangleSetup& t, const TileRect& tile, const float* depth,
                        size_t stride, Fragment* out);
// rasterize_tested at the samples of a multisampled tile (Tile::multisampled()): coverage
// per sample with the opaque path's positions and fill rule, each covered sample of the
// tile's surface (Tile::sample_mask) depth-tested LESS against its own depth
// (Tile::depth_at_sample). Appends one fragment per pixel with any sample passing, in the
// order rasterize_tested would; returns how many.
size_t rasterize_tested_samples(const TriangleSetup& t, const Tile& tile, Fragment* out);
// The same one pixel and one sample at a time from the setup's int64 edge functions and
// depth plane (depth_offset_at_sample()), pixels in row order, for the test of the fast path.
size_t rasterize_tested_samples_reference(const TriangleSetup& t, const Tile& tile, Fragment* out);

}  // namespace tessera::pipeline
