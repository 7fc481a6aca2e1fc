// Clipping in homogeneous coordinates (Sutherland-Hodgman): a triangle is cut
// against the near (z >= -w) and far (z <= w) planes and, only where a vertex leaves the guard
// band, against x = +-guard_x*w and y = +-guard_y*w (viewport.h). Cutting at the near plane
// also removes everything at or behind the eye (w <= 0), so triangles crossing w = 0 keep their
// visible part instead of being dropped or wrapping around through infinity.
#pragma once
#include <glm/glm.hpp>

#include <cstdint>

#include "raster/pipeline/viewport.h"

namespace tessera::pipeline {

// Each plane can add at most one vertex to a convex polygon: 3 + 6 planes.
inline constexpr int kMaxClippedVertices = 9;

// Clips the triangle `in` against the planes named in `codes` (ClipCode bits, the union of the
// three vertices' outcodes). Writes the clipped convex polygon, in the triangle's winding, to
// `out` and returns its vertex count (0 when nothing is left).
int clip_triangle(const glm::vec4 in[3], uint32_t codes, const Viewport& viewport,
                  glm::vec4 out[kMaxClippedVertices]);

}  // namespace tessera::pipeline
