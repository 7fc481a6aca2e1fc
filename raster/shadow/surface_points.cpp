#include "raster/shadow/surface_points.h"

#include <algorithm>
#include <cmath>

namespace tessera::shadow {
namespace {

bool finite(const glm::vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// A triangle's plane: a point on it and its (unnormalised) normal; empty when the triangle
// is degenerate, has non-finite vertices or bad indices.
struct Plane {
    glm::vec3 point{0.0f}, normal{0.0f};
    float length = 0.0f;  // |normal|; 0: no plane
};

Plane plane_of(const Mesh& mesh, uint32_t triangle) {
    Plane plane;
    if (size_t(triangle) >= mesh.triangle_count()) return plane;
    const uint32_t* index = &mesh.indices[3 * size_t(triangle)];
    const size_t n = mesh.vertex_count();
    if (index[0] >= n || index[1] >= n || index[2] >= n) return plane;
    plane.point = mesh.positions[index[0]];
    plane.normal = glm::cross(mesh.positions[index[1]] - plane.point,
                              mesh.positions[index[2]] - plane.point);
    const float length = glm::length(plane.normal);
    if (finite(plane.point) && std::isfinite(length) && length > 0.0f) plane.length = length;
    return plane;
}

}  // namespace

void gather_surface_points(const VisibilityBuffer& visibility, const Mesh& mesh,
                           const PixelRays& rays, const TileRect& tile,
                           SurfacePoints& out) {
    out.clear();
    const size_t area = size_t(tile.x1 - tile.x0) * size_t(tile.y1 - tile.y0);
    out.pixel.reserve(area);
    out.position.reserve(area);
    out.normal.reserve(area);
    // The tile's ids are read in 4x4 blocks, which the hardware prefetchers do not follow
    // across rows; when the visibility buffer is cold (written with streaming stores, or
    // long ago) every cache line was a serial miss. Asking for all of them first lets the
    // misses overlap.
    for (int y = tile.y0; y < tile.y1; ++y)
        for (int x = tile.x0; x < tile.x1; x += 16)
            __builtin_prefetch(&visibility.triangle[size_t(y) * size_t(visibility.width) + size_t(x)]);
    constexpr int kBlock = 4;
    uint32_t cached = kNoTriangle;  // neighbouring pixels mostly share a triangle
    Plane plane;
    for (int by = tile.y0; by < tile.y1; by += kBlock)
        for (int bx = tile.x0; bx < tile.x1; bx += kBlock)
            for (int y = by; y < std::min(by + kBlock, tile.y1); ++y)
                for (int x = bx; x < std::min(bx + kBlock, tile.x1); ++x) {
                    const size_t pixel = size_t(y) * size_t(visibility.width) + size_t(x);
                    const uint32_t triangle = visibility.triangle[pixel];
                    if (triangle == kNoTriangle) continue;
                    if (triangle != cached) {
                        plane = plane_of(mesh, triangle);
                        cached = triangle;
                    }
                    if (plane.length == 0.0f) continue;
                    glm::vec3 origin, direction;
                    rays.pixel_ray(x, y, origin, direction);
                    // Ray-plane intersection: t = n.(a - o) / n.d (edge-on planes give inf/NaN).
                    const float facing = glm::dot(plane.normal, direction);
                    const float t = glm::dot(plane.normal, plane.point - origin) / facing;
                    const glm::vec3 position = origin + t * direction;
                    if (!finite(position)) continue;
                    out.pixel.push_back(uint32_t(pixel));
                    out.position.push_back(position);
                    out.normal.push_back((facing > 0.0f ? -plane.normal : plane.normal) /
                                         plane.length);
                }
}

}  // namespace tessera::shadow
