// An axis-aligned box centred on the origin: six faces of four vertices each (not shared, so
// every face has its own normal and a full 0..1 uv square, as a textured, normal-mapped cube
// needs), two counter-clockwise triangles per face seen from outside.
#pragma once
#include <glm/glm.hpp>

#include "raster/core/mesh.h"

namespace tessera::geometry {

// Throws std::invalid_argument unless every half extent is positive.
Mesh box_mesh(glm::vec3 half_extent);

}  // namespace tessera::geometry
