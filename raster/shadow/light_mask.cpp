#include "raster/shadow/light_mask.h"

#include <tbb/enumerable_thread_specific.h>

#include <stdexcept>
#include <string>

#include "raster/core/tile.h"

namespace tessera::shadow {

LightMask compute_light_mask(const VisibilityBuffer& visibility, const Mesh& mesh,
                             const glm::mat4& view_projection,
                             std::span<const glm::vec3> lights, const LightTest& test) {
    if (lights.size() > kMaxLights)
        throw std::invalid_argument(std::to_string(lights.size()) + " lights; at most " +
                                    std::to_string(kMaxLights) + " can cast shadows");
    LightMask mask{visibility.width, visibility.height, {}};
    mask.bits.assign(size_t(mask.width) * size_t(mask.height), 0);
    if (mask.bits.empty()) return mask;
    const PixelRays rays(view_projection, visibility.width, visibility.height);
    // Per-thread scratch: a 1080p frame has about 2000 tiles, each of which would otherwise
    // allocate its point lists anew.
    struct Scratch {
        SurfacePoints points;
        std::vector<uint8_t> visible;
    };
    tbb::enumerable_thread_specific<Scratch> scratch;
    parallel_for_tiles(TileGrid(visibility.width, visibility.height, kRayTileSize), [&](int, const TileRect& tile) {
        Scratch& local = scratch.local();
        SurfacePoints& points = local.points;
        std::vector<uint8_t>& visible = local.visible;
        gather_surface_points(visibility, mesh, rays, tile, points);
        visible.assign(points.size(), 0);
        if (!lights.empty()) test(points, lights, visible);
        for (size_t i = 0; i < points.size(); ++i) mask.bits[points.pixel[i]] = visible[i];
    });
    return mask;
}

void facing_lights(const SurfacePoints& points, std::span<const glm::vec3> lights,
                   std::span<uint8_t> visible) {
    for (size_t i = 0; i < points.size(); ++i)
        for (size_t l = 0; l < lights.size(); ++l)
            if (faces_light(points.position[i], points.normal[i], lights[l]))
                visible[i] |= uint8_t(1u << l);
}

}  // namespace tessera::shadow
