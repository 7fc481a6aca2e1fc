// Shadow edges under multisampling: which pixels test their lights again at every sample.
//
// MSAA shades each surface of a pixel once (coverage_layers.h), so a shadow boundary that
// crosses a surface stays as jagged as in a one-sample frame. Testing the lights at every
// sample of every pixel would multiply the shadow work by the sample count; but a boundary
// shows itself as neighbouring pixels whose tests disagree, so only those pixels are tested
// again, at each sample position, and shaded as the average of their samples' lighting (in
// linear light, like the resolve). This is the edge detection of adaptive supersampling
// (Whitted, "An improved illumination model for shaded display", 1980) applied to the shadow
// test alone.
//
// Only pixels wholly covered by their surface qualify: their samples lie on the surface, so
// the plane extended to each sample is the surface. A partly covered pixel is on a geometric
// edge, which the coverage already smooths, and its plane extended to the other samples could
// sink under its neighbours. A pixel on the tile's border has neighbours the tile does not
// hold (the next tile may not be rasterized yet); it qualifies whenever it is wholly covered,
// so the decision never depends on another tile, hence never on the thread count.
#pragma once
#include <cstdint>
#include <span>
#include <vector>

#include "raster/core/tile.h"
#include "raster/shadow/surface_points.h"

namespace tessera::shadow {

// Appends to `edges` the indices of the points of `tile` (gathered from it, image_width
// pixels to a row) to test again at each of `samples` samples: points whose pixel is wholly
// covered by its surface (Tile::coverage == samples, or no coverage) and lies on the tile's
// border or has a 4-neighbour in the tile whose point was given other lights (`lights[i]`:
// the lights reaching point i). `scratch`: per-thread working memory.
void find_shadow_edges(const Tile& tile, size_t image_width, const SurfacePoints& points,
                       std::span<const uint8_t> lights, int samples, std::vector<uint16_t>& scratch,
                       std::vector<uint32_t>& edges);

}  // namespace tessera::shadow
