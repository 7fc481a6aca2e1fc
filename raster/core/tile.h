// Fixed square image tiles run in parallel by oneTBB: one task per tile (simple_partitioner,
// grain one tile), so the work split never depends on the thread count. 32x32 pixels is
// about 1024 rays or lookups per task, above oneTBB's 100k-cycle grain rule.
#pragma once
#include <tbb/blocked_range2d.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>

#include <algorithm>

namespace tessera {

inline constexpr int kTileSize = 32;

struct ImageTile {
    int x0, y0, x1, y1;  // pixels [x0, x1) x [y0, y1)
};

// Calls body(ImageTile) once per tile of a width x height image, in parallel.
template <class Body>
void parallel_for_tiles(int width, int height, const Body& body) {
    const int tiles_x = (width + kTileSize - 1) / kTileSize;
    const int tiles_y = (height + kTileSize - 1) / kTileSize;
    tbb::parallel_for(
        tbb::blocked_range2d<int>(0, tiles_y, 1, 0, tiles_x, 1),
        [&](const tbb::blocked_range2d<int>& tiles) {
            for (int ty = tiles.rows().begin(); ty != tiles.rows().end(); ++ty)
                for (int tx = tiles.cols().begin(); tx != tiles.cols().end(); ++tx)
                    body(ImageTile{tx * kTileSize, ty * kTileSize,
                                   std::min(width, (tx + 1) * kTileSize),
                                   std::min(height, (ty + 1) * kTileSize)});
        },
        tbb::simple_partitioner());
}

}  // namespace tessera
