// Cascaded shadow maps: where a light's maps look, fitted to what the camera sees.
//
// The camera's view depths that meet the scene are split into cascades by the practical
// split scheme of parallel-split shadow maps (Zhang et al. 2006): split i of n between near
// n and far f is
//     blend * n (f/n)^(i/N) + (1 - blend) * (n + (f - n) i/N),
// logarithmic splits (texel size proportional to view depth, what perspective aliasing asks
// for) blended with uniform ones (which keep the far cascades from growing too large).
//
// Each cascade's map covers the bounding sphere of its slice of the view frustum. The sphere
// is computed in the camera's own space, so it does not change as the camera turns or moves:
// the map's size in the world (its texel size) stays put. For a distant (directional) light
// the map is an orthographic view along the light whose window is moved only in whole
// texels ("texel snapping", Microsoft's "Common Techniques to Improve Shadow Depth Maps"):
// a world point then falls at the same place within its texel from frame to frame, and
// shadow edges do not shimmer as the camera moves. The depth range reaches back to the
// scene's bounds, so casters outside the slice still cast into it. The far end of the
// shadowed depths is rounded up to a step of 2^(1/8), so the splits, too, change only at
// those steps in an animation.
//
// A point light gets a perspective view from the light onto each slice's sphere (no texel
// snapping: a perspective map's texels are not a fixed grid in the world).
#pragma once
#include <glm/glm.hpp>

#include <array>
#include <limits>
#include <vector>

#include "raster/core/camera.h"
#include "raster/core/mesh.h"

namespace tessera::shadow {

struct Bounds {
    glm::vec3 lo{std::numeric_limits<float>::infinity()};
    glm::vec3 hi{-std::numeric_limits<float>::infinity()};
    bool empty() const { return !(lo.x <= hi.x); }
};

// Bounds of the mesh's finite vertices.
Bounds mesh_bounds(const Mesh& mesh);

// count + 1 view depths from near to far (the first near, the last far) by the practical
// split scheme above; blend in [0, 1].
std::vector<float> cascade_splits(float near, float far, int count, float blend);

// The view depths (distances along the camera's view axis) worth shadowing: from the
// camera's near plane, or the nearest corner of `scene` if farther, to the farthest corner
// of `scene` rounded up to a step of near * 2^(k/8), but not beyond the far plane. {near,
// near} when the scene is empty or entirely behind the camera.
std::array<float, 2> shadowed_depths(const Camera& camera, const Bounds& scene);

// The 8 corners of the camera's view frustum between view depths d0 and d1 (its window,
// if any, included), in world space: d0's four first.
std::array<glm::vec3, 8> frustum_slice(const Camera& camera, float d0, float d1);

// The sphere around a slice, in the camera's own space (so the same for any pose).
struct Sphere {
    glm::vec3 centre{0.0f};
    float radius = 0.0f;
};
Sphere slice_sphere(const Camera& camera, float d0, float d1);

// One map's view of the light.
struct LightProjection {
    glm::mat4 view_projection{1.0f};
    glm::vec3 axis{0.0f, 0.0f, -1.0f};  // unit view direction of the light
    // World size of one texel at a receiver: texel_size + texel_per_depth * (its depth along
    // axis from the light); orthographic views have texel_per_depth 0.
    float texel_size = 0.0f;
    float texel_per_depth = 0.0f;
};

// A distant light shining along -towards_light: an orthographic view covering `sphere`
// (world space) with `resolution` texels a side, texel-snapped, its depth range from the
// near side of `scene` to the far side of the sphere.
LightProjection fit_distant_light(const glm::vec3& towards_light, const Sphere& sphere,
                                  const Bounds& scene, int resolution);

// A point light at `light`: a perspective view onto `sphere` (world space) whose depth range
// starts at the near side of `scene`; from inside the sphere, a 120-degree view towards it.
LightProjection fit_point_light(const glm::vec3& light, const Sphere& sphere, const Bounds& scene,
                                int resolution);

// The sphere around the scene's bounds.
Sphere bounds_sphere(const Bounds& scene);

}  // namespace tessera::shadow
