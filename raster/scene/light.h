// Lights: a homogeneous world position wLiPos (w = 1: a point light at xyz,
// w = 0: a directional light shining from direction xyz), ambient radiance La and emitted
// radiance Le. The light vector at a surface point p is wLiPos.xyz - p * wLiPos.w, which covers
// both kinds with one formula (as a vertex shader would). shadow_map says how the light's
// shadow maps are made when shadows come from maps.
#pragma once
#include <glm/glm.hpp>

#include "raster/core/shadow_map_settings.h"

namespace tessera::scene {

struct Light {
    glm::vec4 position{0.0f, 0.0f, 1.0f, 0.0f};
    glm::vec3 La{0.1f};
    glm::vec3 Le{1.0f};
    ShadowMapSettings shadow_map;
};

inline Light point_light(glm::vec3 position, glm::vec3 La, glm::vec3 Le) {
    return {glm::vec4(position, 1.0f), La, Le, {}};
}

// `towards_light` points from the scene to the light (need not be unit length).
inline Light directional_light(glm::vec3 towards_light, glm::vec3 La, glm::vec3 Le) {
    return {glm::vec4(towards_light, 0.0f), La, Le, {}};
}

}  // namespace tessera::scene
