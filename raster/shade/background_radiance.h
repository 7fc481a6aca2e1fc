// The radiance of a scene's background along a ray: the full-screen environment pass of
// ray-marching renderers. The ray direction of a pixel is the camera's:
// d = u * x_ndc / P00 + v * y_ndc / P11 - w (the inverse of the view and projection matrices,
// "rayDirMatrix", restricted to directions).
//
// Two forms: one direction (the reference, and what reflections look up), and kLanes
// directions at once for the per-pixel background passes. The sky is one template over float
// and simd::vfloat, so the lane form equals the one-direction form bit for bit at every lane
// width; a cube map is sampled one lane at a time.
#pragma once
#include <glm/glm.hpp>

#include "raster/scene/background.h"
#include "raster/simd/lane_math.h"

namespace tessera::shade {

// Radiance seen along `direction` (any length; zero, infinite or NaN gives (0, 0, -1)).
glm::vec3 background_radiance(const scene::Background& background, glm::vec3 direction);

// The same along kLanes directions (one per lane), equal lane by lane to the form above.
simd::V3<simd::vfloat> background_radiance_lanes(const scene::Background& background,
                                                 const simd::V3<simd::vfloat>& direction);

}  // namespace tessera::shade
