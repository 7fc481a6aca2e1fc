// The parametric surfaces as SurfaceFunctions for tessellate(): each gives the
// position, the analytic partial derivatives and the analytic normal (dr/du x dr/dv, or the
// closed form where the cross product vanishes at a pole).
#pragma once
#include <glm/glm.hpp>

#include <span>

#include "raster/geometry/param_surface.h"

namespace tessera::geometry {

// Seed: n = (cos 2pi u sin pi v, sin 2pi u sin pi v, cos pi v), p = c + R n.
SurfaceFunction sphere_surface(glm::vec3 center, float radius);

// p = c + (a cos 2pi u sin pi v, b sin 2pi u sin pi v, c cos pi v); the normal is the gradient
// of the implicit form (x/a, y/b, z/c) scaled, which equals dr/du x dr/dv away from the poles.
SurfaceFunction ellipsoid_surface(glm::vec3 center, glm::vec3 radii);

// Ring of radius `major` in the xy plane, tube of radius `minor`:
// p = ((R + r cos 2pi v) cos 2pi u, (R + r cos 2pi v) sin 2pi u, r sin 2pi v).
SurfaceFunction torus_surface(float major, float minor);

// The waving flag: p = (u W, v H, sin(K pi u + phase) D),
// n = (-K pi cos(K pi u + phase) D, 0, W) (the cross product divided by H).
SurfaceFunction flag_surface(float width, float height, float depth, float waves, float phase);

// A heightfield over the xz plane, `heights` row-major with `columns` samples along x and
// `rows` along z (at least 2 x 2), spanning `size` (x, z) centred on the origin, y = height *
// `height_scale`. Tessellate it at exactly (columns - 1) x (rows - 1) to get one vertex per
// sample. Normals come from central differences of the samples (one-sided at the border):
// n = (-dh/dx, 1, -dh/dz). Throws std::invalid_argument for a size mismatch. The function
// keeps a reference to `heights`, which must outlive the tessellation.
SurfaceFunction heightfield_surface(std::span<const float> heights, int columns, int rows,
                                    glm::vec2 size, float height_scale);

}  // namespace tessera::geometry
