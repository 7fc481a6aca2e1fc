#include "raster/embree/tile_passes.h"

#include <tbb/blocked_range2d.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>

#include <algorithm>
#include <cstring>
#include <stdexcept>

#include "raster/pipeline/vertex_stage.h"

namespace tessera::embree {

void run_tile_passes(const Mesh& mesh, const glm::mat4& view_projection,
                     const pipeline::Viewport& viewport, VisibilityBuffer& visibility,
                     std::span<const pipeline::TilePass> passes, std::vector<glm::vec4>* color,
                     const glm::vec4& clear_color) {
    if (visibility.width != viewport.width || visibility.height != viewport.height)
        throw std::invalid_argument("visibility buffer and viewport differ in size");
    pipeline::ClipVertices clip;
    pipeline::run_vertex_stage(mesh, view_projection, viewport, clip);
    if (color) color->assign(size_t(viewport.width) * size_t(viewport.height), clear_color);
    constexpr int kTile = 64;
    const int tiles_x = (viewport.width + kTile - 1) / kTile;
    const int tiles_y = (viewport.height + kTile - 1) / kTile;
    tbb::parallel_for(
        tbb::blocked_range2d<int>(0, tiles_y, 1, 0, tiles_x, 1),
        [&](const tbb::blocked_range2d<int>& tiles) {
            std::vector<glm::vec4> tile_color(size_t(kTile) * kTile);
            for (int ty = tiles.rows().begin(); ty != tiles.rows().end(); ++ty)
                for (int tx = tiles.cols().begin(); tx != tiles.cols().end(); ++tx) {
                    pipeline::TileContext context;
                    context.rect = {tx * kTile, ty * kTile,
                                    std::min(viewport.width, (tx + 1) * kTile),
                                    std::min(viewport.height, (ty + 1) * kTile)};
                    context.viewport = &viewport;
                    context.mesh = &mesh;
                    context.clip = &clip;
                    const size_t origin =
                        size_t(context.rect.y0) * size_t(viewport.width) + size_t(context.rect.x0);
                    context.triangle = visibility.triangle.data() + origin;
                    context.depth = visibility.depth.data() + origin;
                    context.stride = size_t(viewport.width);
                    std::fill(tile_color.begin(), tile_color.end(), clear_color);
                    context.color = tile_color.data();
                    context.color_stride = size_t(kTile);
                    for (const pipeline::TilePass& pass : passes) pass(context);
                    if (color)
                        for (int y = 0; y < context.height(); ++y)
                            std::memcpy(color->data() + size_t(context.rect.y0 + y) * viewport.width +
                                            size_t(context.rect.x0),
                                        tile_color.data() + size_t(y) * kTile,
                                        size_t(context.width()) * sizeof(glm::vec4));
                }
        },
        tbb::simple_partitioner());
}

}  // namespace tessera::embree
