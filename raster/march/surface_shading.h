// Shading of a marched hit (seeds/003 homework: "Phong BRDF or environment mapping"):
// Blinn-Phong with one directional light as in seeds/000,
//     L = ka La + (kd cos(theta) + ks cos(delta)^shine) Le,
// cos(theta) = N.L, cos(delta) = N.H with H the half vector, plus an environment-mapped mirror
// term: `reflectivity` of the radiance the environment sends along reflect(d, N).
#pragma once
#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>

#include "raster/march/environment.h"

namespace tessera::march {

struct SurfaceMaterial {
    glm::vec3 diffuse{0.75f, 0.55f, 0.35f};  // kd
    glm::vec3 specular{0.35f};               // ks
    float shininess = 48.0f;
    glm::vec3 ambient{0.12f};   // ka La
    float reflectivity = 0.0f;  // 0: pure Blinn-Phong, 1: a mirror of the environment
};

struct DirectionalLight {
    glm::vec3 direction{0.4f, 0.55f, -0.73f};  // towards the light, unit length
    glm::vec3 radiance{1.0f};                  // Le
};

// `d` is the unit ray direction, `n` the unit outward normal at the hit.
inline glm::vec3 shade_surface(const SurfaceMaterial& m, const DirectionalLight& light,
                               const Environment& environment, glm::vec3 d, glm::vec3 n) {
    const glm::vec3 v = -d;
    const float cos_theta = std::max(glm::dot(n, light.direction), 0.0f);
    const glm::vec3 h = glm::normalize(light.direction + v);
    // No highlight on the side facing away from the light.
    const float cos_delta = cos_theta > 0.0f ? std::max(glm::dot(n, h), 0.0f) : 0.0f;
    const glm::vec3 direct = m.diffuse * cos_theta + m.specular * std::pow(cos_delta, m.shininess);
    glm::vec3 colour = m.ambient * m.diffuse + direct * light.radiance;
    if (m.reflectivity > 0.0f)
        colour = glm::mix(colour, environment.radiance(glm::reflect(d, n)), m.reflectivity);
    return colour;
}

}  // namespace tessera::march
