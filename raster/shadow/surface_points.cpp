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
                           const PixelRays& rays, const TileRect& rect,
                           SurfacePoints& out) {
    Tile tile;
    tile.rect = rect;
    tile.triangle = const_cast<uint32_t*>(visibility.triangle.data()) + size_t(rect.y0) * size_t(visibility.width) +
                    size_t(rect.x0);
    tile.stride = size_t(visibility.width);
    gather_surface_points(tile, size_t(visibility.width), mesh, rays, out);
}

void gather_surface_points(const Tile& tile, size_t image_width, const Mesh& mesh, const PixelRays& rays,
                           SurfacePoints& out) {
    out.clear();
    const TileRect& rect = tile.rect;
    const size_t area = size_t(rect.width()) * size_t(rect.height());
    out.pixel.reserve(area);
    out.position.reserve(area);
    out.normal.reserve(area);
    // The tile's ids are read in 4x4 blocks, which the hardware prefetchers do not follow
    // across rows; when the visibility buffer is cold (written with streaming stores, or
    // long ago) every cache line was a serial miss. Asking for all of them first lets the
    // misses overlap.
    for (int y = rect.y0; y < rect.y1; ++y)
        for (int x = rect.x0; x < rect.x1; x += 16) __builtin_prefetch(&tile.triangle_at(x, y));
    constexpr int kBlock = 4;
    uint32_t cached = kNoTriangle;  // neighbouring pixels mostly share a triangle
    Plane plane;
    for (int by = rect.y0; by < rect.y1; by += kBlock)
        for (int bx = rect.x0; bx < rect.x1; bx += kBlock)
            for (int y = by; y < std::min(by + kBlock, rect.y1); ++y)
                for (int x = bx; x < std::min(bx + kBlock, rect.x1); ++x) {
                    const size_t pixel = size_t(y) * image_width + size_t(x);
                    const uint32_t triangle = tile.triangle_at(x, y);
                    if (triangle == kNoTriangle) continue;
                    if (triangle != cached) {
                        plane = plane_of(mesh, triangle);
                        cached = triangle;
                    }
                    if (plane.length == 0.0f) continue;
                    glm::vec3 origin, direction;
                    if (tile.centroid) {  // a point on the surface (coverage_layers.h)
                        const glm::vec2 at = tile.centroid[tile.offset(x, y)];
                        rays.ray(float(x) + 0.5f + at.x, float(y) + 0.5f + at.y, origin, direction);
                    } else {
                        rays.pixel_ray(x, y, origin, direction);
                    }
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
