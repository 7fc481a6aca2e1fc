#include "raster/embree/tile_passes.h"

#include <tbb/enumerable_thread_specific.h>

#include <algorithm>
#include <cstring>
#include <stdexcept>

#include "raster/core/tile.h"
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
    const TileGrid grid(viewport.width, viewport.height, 64);
    tbb::enumerable_thread_specific<std::vector<glm::vec4>> tile_colours;
    parallel_for_tiles(grid, [&](int, const TileRect& rect) {
        std::vector<glm::vec4>& tile_colour = tile_colours.local();
        tile_colour.assign(size_t(grid.size) * size_t(grid.size), clear_color);
        pipeline::TileContext context;
        context.rect = rect;
        const size_t origin = size_t(rect.y0) * size_t(viewport.width) + size_t(rect.x0);
        context.triangle = visibility.triangle.data() + origin;
        context.depth = visibility.depth.data() + origin;
        context.stride = size_t(viewport.width);
        context.colour = tile_colour.data();
        context.colour_stride = size_t(grid.size);
        context.viewport = &viewport;
        context.mesh = &mesh;
        context.clip = &clip;
        for (const pipeline::TilePass& pass : passes) pass(context);
        if (color)
            for (int y = 0; y < rect.height(); ++y)
                std::memcpy(color->data() + size_t(rect.y0 + y) * viewport.width + size_t(rect.x0),
                            tile_colour.data() + size_t(y) * grid.size, size_t(rect.width()) * sizeof(glm::vec4));
    });
}

}  // namespace tessera::embree
