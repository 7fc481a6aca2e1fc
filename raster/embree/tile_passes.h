// The tile passes (shading, compute passes) over a visibility buffer that did not come from
// the rasterizer: the ray-cast renderer's step 4b, so that its pixels are shaded by exactly
// the code that shades the rasterizer's (tile_pass.h).
//
// The passes see the same TileContext as under the rasterizer: the frame's mesh, its
// clip-space vertices from the same vertex stage (so perspective-correct barycentrics are
// bit-identical), tile views of the visibility buffer and a tile colour buffer cleared to
// `clear_color`. Tiles are 64x64 pixels (the rasterizer's default) and run in parallel.
// Transparency is not part of this path: rays treat every triangle as opaque, and a pass
// must not call TileContext::for_each_transparent (there are no bins to replay).
#pragma once
#include <glm/glm.hpp>

#include <span>
#include <vector>

#include "raster/core/mesh.h"
#include "raster/pipeline/tile_pass.h"
#include "raster/pipeline/viewport.h"
#include "raster/core/visibility.h"

namespace tessera::embree {

// Runs `passes` over every tile of `visibility` (sized to `viewport`). `color`, when given,
// is resized to width*height and receives the tile colour after the passes.
void run_tile_passes(const Mesh& mesh, const glm::mat4& view_projection,
                     const pipeline::Viewport& viewport, VisibilityBuffer& visibility,
                     std::span<const pipeline::TilePass> passes, std::vector<glm::vec4>* color = nullptr,
                     const glm::vec4& clear_color = glm::vec4(0.0f));

}  // namespace tessera::embree
