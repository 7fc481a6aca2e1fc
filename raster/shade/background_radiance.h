// The radiance of a scene's background along a ray: the full-screen environment pass of
// ray-marching renderers. The ray direction of a pixel is the camera's:
// d = u * x_ndc / P00 + v * y_ndc / P11 - w (the inverse of the view and projection matrices,
// "rayDirMatrix", restricted to directions).
#pragma once
#include <glm/glm.hpp>

#include "raster/scene/background.h"

namespace tessera::shade {

// Radiance seen along `direction` (any length; zero gives the horizon).
glm::vec3 background_radiance(const scene::Background& background, glm::vec3 direction);

}  // namespace tessera::shade
