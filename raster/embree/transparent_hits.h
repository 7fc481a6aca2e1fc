// The transparent pass of the ray-cast renderer. The rasterizer leaves transparent triangles
// out of its opaque pass and then, per tile, hands each one's fragments in front of the
// opaque depth to blending, triangle by triangle in submission order (tile_pass.h,
// TileContext::for_each_transparent). This does the same with rays: each pixel's primary ray
// collects the transparent triangles it passes before the opaque surface (an Embree context
// filter records them and lets traversal go on), and the fragments are handed out in the
// same shape and order, so blending is shared and both renderers give the same picture.
// Depth is compared as the rasterizer does: the hit triangle's window depth at the pixel
// centre (PixelRays::depth_plane), LESS than the opaque depth there.
#pragma once
#include <cstdint>
#include <functional>
#include <span>

#include "raster/core/pixel_rays.h"
#include "raster/embree/scene.h"
#include "raster/core/tile.h"
#include "raster/pipeline/tile_raster.h"
#include "raster/core/visibility.h"

namespace tessera::embree {

// Calls blend(triangle, its fragments in the tile) once per transparent triangle
// (transparent[t] != 0) seen in front of the depth of `opaque`, in increasing triangle id,
// fragments in row order.
void for_each_transparent_hit(const RayScene& scene, const PixelRays& rays, std::span<const uint8_t> transparent,
                              const Tile& opaque,
                              const std::function<void(uint32_t triangle, std::span<const pipeline::Fragment>)>& blend);

}  // namespace tessera::embree
