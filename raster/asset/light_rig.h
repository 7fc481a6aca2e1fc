// The default light rig for a model that brings no lights: a key light above and to the left of
// the camera and a weaker fill light low on the right (the photographer's two-light set-up),
// placed relative to the view so every framing is lit alike. Both are point lights four
// bounding-sphere radii from the model's centre: far enough to light it almost evenly, close
// enough that shadow maps and shadow rays see them outside the model at any scale (the
// Blinn-Phong formula has no distance falloff). Ambient: 0.12 of the key's, scaled by each
// material's ka (the imported materials set ka = kd).
#pragma once
#include <glm/glm.hpp>

#include <vector>

#include "raster/core/camera.h"
#include "raster/scene/light.h"

namespace tessera::asset {

std::vector<scene::Light> default_light_rig(const Camera& camera, glm::vec3 lower, glm::vec3 upper);

}  // namespace tessera::asset
