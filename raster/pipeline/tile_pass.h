// The per-tile pass hook: after a tile's visibility is final, the rasterizer runs a list of
// tile passes on it, in order, while the tile is hot in cache. Shading, transparency and
// compute passes (ray marching, fog) plug in here; they never see how visibility was found.
//
// Passes run concurrently on different tiles (never twice on one tile at the same time), so a
// pass must only write its own tile's pixels and otherwise read shared data.
#pragma once
#include <glm/glm.hpp>

#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>

#include "raster/core/mesh.h"
#include "raster/pipeline/tile_raster.h"
#include "raster/pipeline/vertex_stage.h"
#include "raster/pipeline/viewport.h"

namespace tessera::pipeline {

struct TileWork;  // the rasterizer's view of one tile (bins), opaque to passes

struct TileContext {
    TileRect rect;                 // frame pixels [x0, x1) x [y0, y1) of this tile
    const Viewport* viewport = nullptr;
    const Mesh* mesh = nullptr;             // the frame's world-space mesh
    const ClipVertices* clip = nullptr;     // its clip-space vertices (barycentrics.h)

    // Visibility, row-major with `stride` elements per row, pointing at pixel (x0, y0) of the
    // frame's VisibilityBuffer: triangle id (kNoTriangle where empty) and window depth. Passes
    // that add opaque surfaces (ray marching) may write both.
    uint32_t* triangle = nullptr;
    float* depth = nullptr;
    size_t stride = 0;

    // Linear RGBA colour of the tile, row-major with `color_stride` elements per row, cleared
    // to RasterOptions::clear_color; copied to the frame's colour buffer after the last pass.
    // Null when RasterOptions::tile_color is false.
    glm::vec4* color = nullptr;
    size_t color_stride = 0;

    int width() const { return rect.x1 - rect.x0; }
    int height() const { return rect.y1 - rect.y0; }

    // Rasterizes this tile's transparent triangles (RasterOptions::transparent) in submission
    // order, each depth-tested (LESS) against `depth` as it is now, without writing it, and
    // calls blend(triangle id, its passing fragments) once per triangle that has any.
    void for_each_transparent(
        const std::function<void(uint32_t triangle, std::span<const Fragment> fragments)>& blend) const;

    const TileWork* work = nullptr;
};

using TilePass = std::function<void(const TileContext&)>;

}  // namespace tessera::pipeline
