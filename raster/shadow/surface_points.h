// The visible surface of one image tile as a list of world-space points, the input of both
// shadow tests (Embree shadow rays and shadow-map lookups), so they judge identical points.
//
// Each point is the exact intersection of the pixel-centre ray with the plane of the pixel's
// triangle (from the visibility buffer), not an unprojection of the stored depth: window depth
// near 1 keeps too few bits to place a point within a shadow bias. Points are listed in 4x4
// pixel blocks (row-major blocks, row-major inside), so 16 consecutive points are neighbours:
// what makes a 16-wide shadow-ray packet coherent.
#pragma once
#include <glm/glm.hpp>

#include <cstdint>
#include <span>
#include <vector>

#include "raster/core/pixel_rays.h"
#include "raster/core/scratch_vector.h"
#include "raster/core/tile.h"
#include "raster/core/mesh.h"
#include "raster/core/visibility.h"
#include "raster/simd/simd.h"

namespace tessera::shadow {

// The lists are ScratchVectors: the lanes gather sizes them for a whole tile without writing
// them, stores whole vectors of compressed lanes and trims them at the end.
struct SurfacePoints {
    ScratchVector<uint32_t> pixel;      // index into the image, y * width + x
    ScratchVector<glm::vec3> position;  // world space
    ScratchVector<glm::vec3> normal;    // unit geometric normal, turned towards the camera
    // Bit l set when the point faces lights[l] (faces_light), for the lights given to
    // gather_surface_points; empty without lights.
    ScratchVector<uint8_t> facing;

    size_t size() const { return pixel.size(); }
    void clear() {
        pixel.clear();
        position.clear();
        normal.clear();
        facing.clear();
    }
    // Empties the lists and makes room for a tile of `area` pixels (and their facing bits when
    // `with_facing`), so filling them never reallocates: the start of every gather.
    void start(size_t area, bool with_facing) {
        clear();
        pixel.reserve(area);
        position.reserve(area);
        normal.reserve(area);
        if (with_facing) facing.reserve(area);
    }
};

// Replaces `out` with the covered pixels of `tile`. Pixels whose triangle is degenerate or
// has non-finite vertices (never produced by either renderer, but guarded) are left out.
void gather_surface_points(const VisibilityBuffer& visibility, const Mesh& mesh,
                           const PixelRays& rays, const TileRect& tile,
                           SurfacePoints& out);
// The same for the pixels of a Tile (its triangle ids; pixels it does not hold have none) in
// an image `image_width` pixels wide, through Tile::centroid where it has one; with `lights`,
// also which of them each point faces (SurfacePoints::facing, at most 8 lights).
//
// simd::kLanes pixels of a 4x4 block at a time: the rays through them (PixelRays::rays), each
// pixel's triangle plane from a table of the tile's triangles, and the intersection, the
// normal and the facing tests in float lanes, in gather_surface_points_reference's order of
// operations, so the points are its points bit for bit.
void gather_surface_points(const Tile& tile, size_t image_width, const Mesh& mesh, const PixelRays& rays,
                           SurfacePoints& out, std::span<const glm::vec3> lights = {});
// The definition, one pixel at a time (without facing bits).
void gather_surface_points_reference(const Tile& tile, size_t image_width, const Mesh& mesh, const PixelRays& rays,
                                     SurfacePoints& out);

// The points of the listed `pixels` (indices y * image_width + x, in `tile`) on the rays
// through their centres moved by `at` pixels, computed as the reference computes a point (the
// surface's plane extended: the caller knows the pixel is wholly this surface), with their
// facing bits as gather_surface_points gives them. For the few pixels tested again at their
// samples (shadow_edges.h).
void gather_surface_points_at(const Tile& tile, size_t image_width, const Mesh& mesh, const PixelRays& rays,
                              std::span<const uint32_t> pixels, glm::vec2 at, SurfacePoints& out,
                              std::span<const glm::vec3> lights);

// True when a light at `light` is on the camera's side of the surface at `position` (the
// normal from gather_surface_points faces the camera): only then can it light the point.
inline bool faces_light(const glm::vec3& position, const glm::vec3& normal,
                        const glm::vec3& light) {
    return glm::dot(normal, light - position) > 0.0f;
}

// faces_light for simd::kLanes points, position (px, py, pz) and normal (nx, ny, nz) in
// lanes: glm::dot's operations in its order ((x + y) + z), so each lane's answer is the
// one-point test's.
inline simd::vmask faces_light(simd::vfloat px, simd::vfloat py, simd::vfloat pz, simd::vfloat nx,
                               simd::vfloat ny, simd::vfloat nz, const glm::vec3& light) {
    using simd::vfloat;
    return vfloat(0.0f) < nx * (vfloat(light.x) - px) + ny * (vfloat(light.y) - py) + nz * (vfloat(light.z) - pz);
}

}  // namespace tessera::shadow
