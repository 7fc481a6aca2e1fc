// Which lights reach each pixel's surface: one byte per pixel, bit l set when light l is on
// the camera's side of the surface and nothing occludes it. This is the output of every
// shadow method (none, shadow map, Embree shadow rays), so shading reads one format and the
// methods can be compared pixel by pixel.
#pragma once
#include <glm/glm.hpp>

#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "raster/core/mesh.h"
#include "raster/shadow/surface_points.h"
#include "raster/core/visibility.h"

namespace tessera::shadow {

inline constexpr size_t kMaxLights = 8;  // one bit per light in a byte

struct LightMask {
    int width = 0;
    int height = 0;
    std::vector<uint8_t> bits;  // rows top to bottom; 0 where no triangle covers the pixel
};

// A shadow test for one tile's points: sets visible[i] bit l when lights[l] reaches point i
// (visible arrives zeroed). Called concurrently for different tiles.
using LightTest = std::function<void(const SurfacePoints& points,
                                     std::span<const glm::vec3> lights,
                                     std::span<uint8_t> visible)>;

// Runs `test` over every covered pixel, tile by tile in parallel (fixed 32x32 tiles, so the
// result does not depend on the thread count). Throws std::invalid_argument for more than
// kMaxLights lights.
LightMask compute_light_mask(const VisibilityBuffer& visibility, const Mesh& mesh,
                             const glm::mat4& view_projection,
                             std::span<const glm::vec3> lights, const LightTest& test);

// The unshadowed answer: every light on the camera's side of the surface reaches it.
void facing_lights(const SurfacePoints& points, std::span<const glm::vec3> lights,
                   std::span<uint8_t> visible);

}  // namespace tessera::shadow
