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
#include "raster/core/tile.h"
#include "raster/pipeline/tile_raster.h"
#include "raster/pipeline/vertex_stage.h"
#include "raster/pipeline/viewport.h"

namespace tessera::pipeline {

struct TileWork;  // the rasterizer's view of one tile (bins), opaque to passes

// What a pass gets: the tile (core/tile.h) and what the frame's triangles are. The tile's
// visibility points into the frame's VisibilityBuffer (passes that add opaque surfaces, such
// as ray marching, may write it); its colour is a tile buffer cleared to
// RasterOptions::clear_color and copied to the frame's colour after the last pass (null when
// RasterOptions::tile_color is false).
struct TileContext : Tile {
    const Viewport* viewport = nullptr;
    const Mesh* mesh = nullptr;          // the frame's world-space mesh
    const ClipVertices* clip = nullptr;  // its clip-space vertices (barycentrics.h)
    // The tile's visibility in the rasterizer's stamp layout (TileBuffers, tile_raster.h),
    // when the render keeps it in the tiles (RasterOptions::frame_visibility false; then
    // triangle and depth are null); null otherwise. Lanes outside `rect` hold no triangle
    // a pass may rely on: passes look at the pixels of `rect` only.
    const TileBuffers* stamps = nullptr;

    // Rasterizes this tile's transparent triangles (RasterOptions::transparent) in submission
    // order, each depth-tested (LESS) against `depth` as it is now, without writing it, and
    // calls blend(triangle id, its passing fragments) once per triangle that has any. On a
    // multisampled tile, coverage and the test are per sample of the tile's surface, against
    // the samples' own depths (rasterize_tested_samples; Fragment::mask).
    void for_each_transparent(
        const std::function<void(uint32_t triangle, std::span<const Fragment> fragments)>& blend) const;

    const TileWork* work = nullptr;
};

using TilePass = std::function<void(const TileContext&)>;

}  // namespace tessera::pipeline
