// Tiles: the unit every per-pixel stage works in. A frame is cut into square tiles in
// row-major order; a Tile is one of them seen in the frame's buffers (visibility and
// colour), which is all a pass needs to know, whoever found the visibility (the tile
// rasterizer or Embree's primary rays) and wherever the buffers live (a whole frame or a
// cache-resident tile buffer). parallel_for_tiles is the one loop that runs them.
#pragma once
#include <glm/glm.hpp>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>

#include "raster/core/visibility.h"

namespace tessera {

// Frame pixels [x0, x1) x [y0, y1).
struct TileRect {
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;

    int width() const { return x1 - x0; }
    int height() const { return y1 - y0; }
};

// The pixels of one tile. Each buffer is addressed from the tile's first pixel (x0, y0) with
// its own row stride in elements; accessors take frame coordinates. Any buffer may be null
// when the stage that hands the tile over has none (a depth-only render has no triangle ids,
// a render without colour no colour).
struct Tile {
    TileRect rect;
    uint32_t* triangle = nullptr;  // visible triangle id, kNoTriangle where none (visibility.h)
    float* depth = nullptr;        // window depth, 1.0 where empty; same stride as triangle
    size_t stride = 0;
    glm::vec4* colour = nullptr;   // linear RGBA
    size_t colour_stride = 0;
    // Multisampled frames (coverage_layers.h): per pixel, the samples the surface in this
    // tile covers, same stride as triangle; 0 where the tile holds no surface for the pixel
    // (passes leave such pixels alone). Null: every pixel is wholly this tile's.
    const uint8_t* coverage = nullptr;
    // With coverage: per pixel, where on the pixel the surface is to be evaluated when it
    // must lie on it (shadow tests), as an offset from the pixel centre in pixels; null: the
    // centre.
    const glm::vec2* centroid = nullptr;
    // With coverage, for passes that sample the pixel themselves (ray-marched silhouettes):
    // per pixel, which of its samples the surface in this tile covers (bit s: sample s; same
    // stride as triangle), and the pixel's sample count and positions (offsets from the
    // pixel centre in pixels, y down). Null: the passes evaluate pixel centres only.
    const uint16_t* sample_mask = nullptr;
    int sample_count = 1;
    const glm::vec2* sample_offsets = nullptr;
    // With sample_mask: the window depth of each sample of the pixel as visibility found it
    // (the opaque surface there, 1.0 where none), for passes that depth-test at the samples
    // (transparent triangles): sample s of pixel (x, y) at sample_depth[(y - y0) * row +
    // (x - x0) * pixel_step + s * sample_step]. Null: every sample reads depth_at(x, y).
    const float* sample_depth = nullptr;
    size_t sample_depth_row = 0, sample_depth_pixel_step = 0, sample_depth_sample_step = 0;

    int width() const { return rect.width(); }
    int height() const { return rect.height(); }
    size_t offset(int x, int y) const { return size_t(y - rect.y0) * stride + size_t(x - rect.x0); }
    uint32_t& triangle_at(int x, int y) const { return triangle[offset(x, y)]; }
    bool active(int x, int y) const { return !coverage || coverage[offset(x, y)] != 0; }
    // Whether the passes may sample this tile's pixels at their sample positions.
    bool multisampled() const { return coverage && sample_mask && sample_offsets && sample_count > 1; }
    float& depth_at(int x, int y) const { return depth[offset(x, y)]; }
    float depth_at_sample(int x, int y, int s) const {
        if (!sample_depth) return depth_at(x, y);
        return sample_depth[size_t(y - rect.y0) * sample_depth_row + size_t(x - rect.x0) * sample_depth_pixel_step +
                            size_t(s) * sample_depth_sample_step];
    }
    // The samples of pixel (x, y) this tile's surface covers: sample_mask's where the tile
    // is multisampled, else bit 0 (the pixel centre stands for the pixel).
    uint16_t samples_at(int x, int y) const { return multisampled() ? sample_mask[offset(x, y)] : uint16_t(1); }
    glm::vec4& colour_at(int x, int y) const {
        return colour[size_t(y - rect.y0) * colour_stride + size_t(x - rect.x0)];
    }
};

// The tile `rect` of a whole frame's visibility buffer and of its colour, a row-major array
// of the same size starting at pixel (0, 0) (null: none).
inline Tile frame_tile(VisibilityBuffer& visibility, glm::vec4* colour, const TileRect& rect) {
    const size_t stride = size_t(visibility.width);
    const size_t origin = size_t(rect.y0) * stride + size_t(rect.x0);
    return {rect, visibility.triangle.empty() ? nullptr : visibility.triangle.data() + origin,
            visibility.depth.data() + origin, stride, colour ? colour + origin : nullptr, stride};
}

// The square tiles of a width x height frame, row-major: tile i covers rect(i).
struct TileGrid {
    int width = 0, height = 0, size = 0;
    int tiles_x = 0, tiles_y = 0;

    TileGrid() = default;
    TileGrid(int w, int h, int tile_size)
        : width(w), height(h), size(tile_size), tiles_x((w + tile_size - 1) / tile_size),
          tiles_y((h + tile_size - 1) / tile_size) {}
    int count() const { return tiles_x * tiles_y; }
    TileRect rect(int tile) const {
        const int tx = tile % tiles_x, ty = tile / tiles_x;
        return {tx * size, ty * size, std::min((tx + 1) * size, width), std::min((ty + 1) * size, height)};
    }
};

// The tiles of per-pixel work other than the rasterizer's (rays, shadow lookups): 32x32
// pixels is about 1024 rays or lookups per task, above oneTBB's rule of thumb of 100k cycles
// per task.
inline constexpr int kRayTileSize = 32;

// Calls body(tile index, TileRect) once per tile of `grid`, in parallel: one task per tile
// (simple_partitioner, grain one tile), so the split of the work never depends on the thread
// count, and every tile writes only its own pixels, so neither do the results.
template <class Body>
void parallel_for_tiles(const TileGrid& grid, const Body& body) {
    tbb::parallel_for(
        tbb::blocked_range<int>(0, grid.count(), 1),
        [&](const tbb::blocked_range<int>& tiles) {
            for (int i = tiles.begin(); i != tiles.end(); ++i) body(i, grid.rect(i));
        },
        tbb::simple_partitioner());
}

}  // namespace tessera
