// Tessellation of parametric surfaces: r(u, v) sampled on an
// N x M grid of the unit square, neighbouring samples joined into 2NM triangles, with the
// analytic normal n = dr/du x dr/dv, uv = (u, v) and the tangent dr/du.
//
// The grid keeps (N+1) x (M+1) shared vertices (a naive version emits six unshared vertices per
// quad; sharing is the same surface with a third of the vertex work). The seam at u = 1 and
// v = 1 is duplicated so the texture coordinates stay continuous per triangle. Each quad (i, j)
// gives the triangles (i,j) (i+1,j) (i,j+1) and (i+1,j) (i+1,j+1) (i,j+1), each made
// counter-clockwise as seen from the side the normals point to.
#pragma once
#include <glm/glm.hpp>

#include <functional>

#include "raster/core/mesh.h"

namespace tessera::geometry {

// One point of a surface with its partial derivatives. `normal` is the surface's analytic
// normal (any length, pointing like dr/du x dr/dv); surfaces give it explicitly because the
// cross product vanishes at parametric poles (a sphere's v = 0) where the normal still exists.
struct SurfacePoint {
    glm::vec3 position;
    glm::vec3 dpdu;
    glm::vec3 dpdv;
    glm::vec3 normal;
};

using SurfaceFunction = std::function<SurfacePoint(float u, float v)>;

// Throws std::invalid_argument unless 1 <= n, m and (n+1)(m+1) fits the 32-bit indices.
// Rows of the grid are evaluated in parallel (oneTBB); the result does not depend on the
// thread count. Zero-length normals (degenerate surfaces) become (0, 0, 1) rather than NaN.
Mesh tessellate(const SurfaceFunction& surface, int n, int m);

}  // namespace tessera::geometry
