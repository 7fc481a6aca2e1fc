// The march, background and fog passes as tile passes of the rasterizer (pipeline/tile_pass.h):
// after a tile's visibility is final, the rasterizer calls them in list order while the tile
// is hot, tiles in parallel. A typical list is
//     {shade (the opaque pass), marched surface(s), fog}
// so the marched surfaces depth-test against the shaded triangles and the fog sees both.
#pragma once
#include "raster/core/tile.h"
#include "raster/pipeline/tile_pass.h"

namespace tessera::march {

// Wraps any pass with run(const Tile&) const; the pass is borrowed and must outlive the
// rasterizer's render call.
template <class Pass>
pipeline::TilePass tile_pass(const Pass& pass) {
    return [&pass](const pipeline::TileContext& tile) { pass.run(tile); };
}

}  // namespace tessera::march
