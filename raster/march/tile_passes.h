// The march, background and fog passes as tile passes of the rasterizer (raster/tile_pass.h):
// after a tile's visibility is final, the rasterizer calls them in list order while the tile
// is hot, tiles in parallel. A typical list is
//     {shade (the opaque pass), marched surface(s), fog}
// so the marched surfaces depth-test against the shaded triangles and the fog sees both.
#pragma once
#include "raster/march/pass_target.h"
#include "raster/pipeline/tile_pass.h"

namespace tessera::march {

inline PassTarget pass_target(const pipeline::TileContext& tile) {
    return {tile.rect.x0, tile.rect.y0, tile.rect.x1, tile.rect.y1,
            tile.depth,   tile.stride,  tile.color,   tile.color_stride,
            tile.triangle};
}

// Wraps any pass with run(const PassTarget&) const; the pass is borrowed and must outlive
// the rasterizer's render call.
template <class Pass>
pipeline::TilePass tile_pass(const Pass& pass) {
    return [&pass](const pipeline::TileContext& tile) { pass.run(pass_target(tile)); };
}

}  // namespace tessera::march
