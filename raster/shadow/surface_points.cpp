#include "raster/shadow/surface_points.h"

#include <algorithm>
#include <bit>
#include <cmath>

#include "raster/simd/simd.h"

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

// The plane of the last triangle asked for: neighbouring pixels mostly share a triangle.
struct LastPlane {
    uint32_t triangle = kNoTriangle;
    Plane plane;

    const Plane& of(const Mesh& mesh, uint32_t t) {
        if (t != triangle) {
            plane = plane_of(mesh, t);
            triangle = t;
        }
        return plane;
    }
};

// The point where the ray (origin, direction) meets `plane`, appended to `out` for `pixel`
// with the plane's unit normal turned towards the ray's origin; false (nothing appended) where
// the ray runs along the plane.
bool append_point(const Plane& plane, const glm::vec3& origin, const glm::vec3& direction, uint32_t pixel,
                  SurfacePoints& out) {
    // Ray-plane intersection: t = n.(a - o) / n.d (edge-on planes give inf/NaN).
    const float facing = glm::dot(plane.normal, direction);
    const float t = glm::dot(plane.normal, plane.point - origin) / facing;
    const glm::vec3 position = origin + t * direction;
    if (!finite(position)) return false;
    out.pixel.push_back(pixel);
    out.position.push_back(position);
    out.normal.push_back((facing > 0.0f ? -plane.normal : plane.normal) / plane.length);
    return true;
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

void gather_surface_points_reference(const Tile& tile, size_t image_width, const Mesh& mesh, const PixelRays& rays,
                                     SurfacePoints& out) {
    const TileRect& rect = tile.rect;
    out.start(size_t(rect.width()) * size_t(rect.height()), false);
    // The tile's ids are read in 4x4 blocks, which the hardware prefetchers do not follow
    // across rows; when the visibility buffer is cold (written with streaming stores, or
    // long ago) every cache line was a serial miss. Asking for all of them first lets the
    // misses overlap.
    for (int y = rect.y0; y < rect.y1; ++y)
        for (int x = rect.x0; x < rect.x1; x += 16) __builtin_prefetch(&tile.triangle_at(x, y));
    constexpr int kBlock = 4;
    LastPlane last;
    for (int by = rect.y0; by < rect.y1; by += kBlock)
        for (int bx = rect.x0; bx < rect.x1; bx += kBlock)
            for (int y = by; y < std::min(by + kBlock, rect.y1); ++y)
                for (int x = bx; x < std::min(bx + kBlock, rect.x1); ++x) {
                    const size_t pixel = size_t(y) * image_width + size_t(x);
                    const uint32_t triangle = tile.triangle_at(x, y);
                    if (triangle == kNoTriangle) continue;
                    const Plane& plane = last.of(mesh, triangle);
                    if (plane.length == 0.0f) continue;
                    glm::vec3 origin, direction;
                    if (tile.centroid) {  // a point on the surface (coverage_layers.h)
                        const glm::vec2 at = tile.centroid[tile.offset(x, y)];
                        rays.ray(float(x) + 0.5f + at.x, float(y) + 0.5f + at.y, origin, direction);
                    } else {
                        rays.pixel_ray(x, y, origin, direction);
                    }
                    append_point(plane, origin, direction, uint32_t(pixel), out);
                }
}

void gather_surface_points_at(const Tile& tile, size_t image_width, const Mesh& mesh, const PixelRays& rays,
                              std::span<const uint32_t> pixels, glm::vec2 at, SurfacePoints& out,
                              std::span<const glm::vec3> lights) {
    out.start(pixels.size(), !lights.empty());
    const size_t light_count = std::min(lights.size(), size_t(8));
    LastPlane last;
    for (const uint32_t pixel : pixels) {
        const int x = int(pixel % image_width), y = int(pixel / image_width);
        const uint32_t triangle = tile.triangle_at(x, y);
        if (triangle == kNoTriangle) continue;
        const Plane& plane = last.of(mesh, triangle);
        if (plane.length == 0.0f) continue;
        glm::vec3 origin, direction;
        rays.ray(float(x) + 0.5f + at.x, float(y) + 0.5f + at.y, origin, direction);
        if (!append_point(plane, origin, direction, pixel, out) || lights.empty()) continue;
        uint8_t facing = 0;
        for (size_t l = 0; l < light_count; ++l)
            facing |= uint8_t(faces_light(out.position.back(), out.normal.back(), lights[l]) << l);
        out.facing.push_back(facing);
    }
}

namespace {

// The planes of the triangles a tile shows, by slot (structure of arrays, for the lanes'
// gathers), found through a direct-mapped table of triangle ids.
struct PlaneTable {
    static constexpr uint32_t kLookup = 1u << 12;
    std::vector<float> px, py, pz, nx, ny, nz, length;
    std::vector<uint32_t> id;
    std::vector<int32_t> lookup = std::vector<int32_t>(kLookup, -1);

    void clear() {
        for (uint32_t t : id) lookup[t & (kLookup - 1)] = -1;
        for (std::vector<float>* v : {&px, &py, &pz, &nx, &ny, &nz, &length}) v->clear();
        id.clear();
    }
    int32_t slot(const Mesh& mesh, uint32_t triangle) {
        int32_t& entry = lookup[triangle & (kLookup - 1)];
        if (entry >= 0 && id[size_t(entry)] == triangle) return entry;
        const Plane p = plane_of(mesh, triangle);
        entry = int32_t(id.size());
        id.push_back(triangle);
        px.push_back(p.point.x), py.push_back(p.point.y), pz.push_back(p.point.z);
        nx.push_back(p.normal.x), ny.push_back(p.normal.y), nz.push_back(p.normal.z);
        length.push_back(p.length);
        return entry;
    }
};

simd::vmask finite_lanes(simd::vfloat v) {
    const simd::vint exponent(0x7F800000);
    return simd::andnot((simd::bits_of(v) & exponent) == exponent, simd::vmask(true));
}

}  // namespace

void gather_surface_points(const Tile& tile, size_t image_width, const Mesh& mesh, const PixelRays& rays,
                           SurfacePoints& out, std::span<const glm::vec3> lights) {
    using simd::kLanes;
    using simd::vfloat;
    using simd::vint;
    using simd::vmask;
    static_assert(16 % kLanes == 0, "lane groups tile a 4x4 block");
    const TileRect& rect = tile.rect;
    const size_t light_count = std::min(lights.size(), size_t(8));
    // Room for every pixel of the tile and one vector of lanes past it: each group stores whole
    // vectors of its kept lanes, compressed, at the end of the lists (scratch storage, so the
    // sizing writes nothing), which are trimmed to the points kept at the end.
    const size_t room = size_t(rect.width()) * size_t(rect.height()) + size_t(kLanes);
    out.clear();
    out.pixel.resize(room);
    out.position.resize(room);
    out.normal.resize(room);
    if (light_count > 0) out.facing.resize(room);
    size_t n = 0;
    for (int y = rect.y0; y < rect.y1; ++y)  // the ids' lines, before the blocks read them (see the reference)
        for (int x = rect.x0; x < rect.x1; x += 16) __builtin_prefetch(&tile.triangle_at(x, y));
    thread_local PlaneTable planes;
    planes.clear();
    constexpr int kBlock = 4;
    alignas(64) float xc[kLanes], yc[kLanes], ox[kLanes], oy[kLanes], oz[kLanes], dx[kLanes], dy[kLanes], dz[kLanes];
    alignas(64) int32_t slot[kLanes], pixel[kLanes], taken[kLanes];
    const PixelRays::RayArrays ray_out{ox, oy, oz, dx, dy, dz};
    const vmask all(true);
    for (int by = rect.y0; by < rect.y1; by += kBlock)
        for (int bx = rect.x0; bx < rect.x1; bx += kBlock)
            for (int first = 0; first < kBlock * kBlock; first += kLanes) {
                // Lane i: pixel (bx + (first + i) % 4, by + (first + i) / 4), row-major in the
                // block like the reference; lanes outside the tile, without a triangle or on a
                // degenerate one (no plane) are off. s: each lane's plane slot.
                vmask on;
                vint s, pixel_index;
                if (!tile.centroid && bx + kBlock <= rect.x1 && by + kBlock <= rect.y1) {
                    // A block inside the tile, at pixel centres: the ids by a gather, centres
                    // and pixel indices in lanes (the values the loop below gives), and one
                    // plane lookup per triangle the group shows: the lowest lane not yet
                    // assigned names it, a compare finds its other lanes.
                    const vint lane = simd::lane_index() + vint(first);
                    const vint lx = lane & vint(kBlock - 1), ly = lane >> vint(2);
                    static_assert(kBlock == 4, "lane >> 2 is the row in the block");
                    const vint x = vint(bx) + lx, y = vint(by) + ly;
                    const vint at = (y - vint(rect.y0)) * vint(int32_t(tile.stride)) + (x - vint(rect.x0));
                    const vint id = simd::bits_of(simd::gather(reinterpret_cast<const float*>(tile.triangle), at));
                    (simd::to_float(x) + vfloat(0.5f)).store(xc);
                    (simd::to_float(y) + vfloat(0.5f)).store(yc);
                    pixel_index = y * vint(int32_t(image_width)) + x;
                    alignas(64) int32_t ids[kLanes];
                    id.store(ids);
                    vmask todo = simd::andnot(id == vint(int32_t(kNoTriangle)), all);
                    on = todo;
                    while (simd::any(todo)) {
                        const uint32_t triangle = uint32_t(ids[std::countr_zero(simd::bits(todo))]);
                        const vmask same = todo & (id == vint(int32_t(triangle)));
                        const int32_t found = planes.slot(mesh, triangle);
                        s = simd::select(same, vint(found), s);
                        if (planes.length[size_t(found)] == 0.0f) on = simd::andnot(same, on);
                        todo = simd::andnot(same, todo);
                    }
                } else {
                    uint32_t cached = kNoTriangle;
                    int32_t cached_slot = 0;
                    for (int i = 0; i < kLanes; ++i) {
                        const int x = bx + (first + i) % kBlock, y = by + (first + i) / kBlock;
                        slot[i] = 0;
                        taken[i] = 0;
                        pixel[i] = 0;
                        xc[i] = yc[i] = 0.5f;
                        if (x >= rect.x1 || y >= rect.y1) continue;
                        const uint32_t triangle = tile.triangle_at(x, y);
                        if (triangle == kNoTriangle) continue;
                        if (triangle != cached) {  // one lookup per run of a triangle
                            cached = triangle;
                            cached_slot = planes.slot(mesh, triangle);
                        }
                        if (planes.length[size_t(cached_slot)] == 0.0f) continue;
                        slot[i] = cached_slot;
                        taken[i] = 1;
                        pixel[i] = int32_t(size_t(y) * image_width + size_t(x));
                        if (tile.centroid) {  // a point on the surface (coverage_layers.h)
                            const glm::vec2 c = tile.centroid[tile.offset(x, y)];
                            xc[i] = float(x) + 0.5f + c.x;
                            yc[i] = float(y) + 0.5f + c.y;
                        } else {
                            xc[i] = float(x) + 0.5f;
                            yc[i] = float(y) + 0.5f;
                        }
                    }
                    on = vint::load(taken) == vint(1);
                    s = vint::load(slot);
                    pixel_index = vint::load(pixel);
                }
                if (!simd::any(on)) continue;
                rays.rays(size_t(kLanes), xc, yc, ray_out);
                const vfloat n_x = simd::gather(planes.nx.data(), s), n_y = simd::gather(planes.ny.data(), s),
                             n_z = simd::gather(planes.nz.data(), s);
                const vfloat o_x = vfloat::load(ox), o_y = vfloat::load(oy), o_z = vfloat::load(oz);
                const vfloat d_x = vfloat::load(dx), d_y = vfloat::load(dy), d_z = vfloat::load(dz);
                // t = n.(a - o) / n.d, glm's dot order ((x + y) + z).
                const vfloat facing = n_x * d_x + n_y * d_y + n_z * d_z;
                const vfloat a_x = simd::gather(planes.px.data(), s) - o_x, a_y = simd::gather(planes.py.data(), s) - o_y,
                             a_z = simd::gather(planes.pz.data(), s) - o_z;
                const vfloat t = (n_x * a_x + n_y * a_y + n_z * a_z) / facing;
                const vfloat p_x = o_x + t * d_x, p_y = o_y + t * d_y, p_z = o_z + t * d_z;
                const vmask kept = on & finite_lanes(p_x) & finite_lanes(p_y) & finite_lanes(p_z);
                if (!simd::any(kept)) continue;
                const vmask flip = vfloat(0.0f) < facing;
                // -n as the reference negates (times -1 is exact, signed zeros included).
                const vfloat length = simd::gather(planes.length.data(), s), minus(-1.0f);
                const vfloat u_x = simd::select(flip, n_x * minus, n_x) / length,
                             u_y = simd::select(flip, n_y * minus, n_y) / length,
                             u_z = simd::select(flip, n_z * minus, n_z) / length;
                // The kept lanes, in lane order (the reference's), appended as whole vectors.
                simd::compress(kept, pixel_index).store_unaligned(reinterpret_cast<int32_t*>(out.pixel.data() + n));
                simd::store_interleaved3(&out.position[n].x, simd::compress(kept, p_x), simd::compress(kept, p_y),
                                         simd::compress(kept, p_z));
                simd::store_interleaved3(&out.normal[n].x, simd::compress(kept, u_x), simd::compress(kept, u_y),
                                         simd::compress(kept, u_z));
                if (light_count > 0) {
                    vint faces(0);
                    for (size_t l = 0; l < light_count; ++l)
                        faces = faces | simd::select(faces_light(p_x, p_y, p_z, u_x, u_y, u_z, lights[l]),
                                                     vint(int32_t(1u << l)), vint(0));
                    simd::store_low_bytes(out.facing.data() + n, simd::compress(kept, faces));
                }
                n += size_t(std::popcount(simd::bits(kept)));
            }
    out.pixel.resize(n);
    out.position.resize(n);
    out.normal.resize(n);
    if (light_count > 0) out.facing.resize(n);
}

}  // namespace tessera::shadow
