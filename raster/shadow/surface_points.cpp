#include "raster/shadow/surface_points.h"

#include <cmath>

namespace tessera::shadow {

void gather_surface_points(const VisibilityBuffer& visibility, const Mesh& mesh,
                           const rt::PixelRays& rays, const rt::ImageTile& tile,
                           SurfacePoints& out) {
    out.clear();
    constexpr int kBlock = 4;
    for (int by = tile.y0; by < tile.y1; by += kBlock)
        for (int bx = tile.x0; bx < tile.x1; bx += kBlock)
            for (int y = by; y < std::min(by + kBlock, tile.y1); ++y)
                for (int x = bx; x < std::min(bx + kBlock, tile.x1); ++x) {
                    const size_t pixel = size_t(y) * size_t(visibility.width) + size_t(x);
                    const uint32_t triangle = visibility.triangle[pixel];
                    if (triangle == kNoTriangle || size_t(triangle) >= mesh.triangle_count())
                        continue;
                    const uint32_t* index = &mesh.indices[3 * size_t(triangle)];
                    if (index[0] >= mesh.vertex_count() || index[1] >= mesh.vertex_count() ||
                        index[2] >= mesh.vertex_count())
                        continue;
                    const glm::vec3 a = mesh.positions[index[0]];
                    const glm::vec3 n = glm::cross(mesh.positions[index[1]] - a,
                                                   mesh.positions[index[2]] - a);
                    glm::vec3 origin, direction;
                    rays.pixel_ray(x, y, origin, direction);
                    // Ray-plane intersection: t = n.(a - o) / n.d (edge-on planes give inf/NaN).
                    const float facing = glm::dot(n, direction);
                    const float t = glm::dot(n, a - origin) / facing;
                    const glm::vec3 position = origin + t * direction;
                    const float length = glm::length(n);
                    if (!std::isfinite(position.x) || !std::isfinite(position.y) ||
                        !std::isfinite(position.z) || !(length > 0.0f) || !std::isfinite(length))
                        continue;
                    out.pixel.push_back(uint32_t(pixel));
                    out.position.push_back(position);
                    out.normal.push_back((facing > 0.0f ? -n : n) / length);
                }
}

}  // namespace tessera::shadow
