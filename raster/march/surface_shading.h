// Shading of a marched hit (Phong BRDF or environment mapping): the
// scene's Blinn-Phong over its lights (shade::blinn_phong, the same formula the
// rasterized triangles get), plus an environment-mapped mirror term: `reflectivity` of the
// radiance the background (sky or cube map) sends along reflect(d, N).
#pragma once
#include <glm/glm.hpp>

#include <span>

#include "raster/scene/light.h"
#include "raster/shade/background_radiance.h"
#include "raster/shade/lighting.h"

namespace tessera::march {

struct SurfaceMaterial {
    glm::vec3 ambient{0.75f, 0.55f, 0.35f};  // ka (multiplies each light's La)
    glm::vec3 diffuse{0.75f, 0.55f, 0.35f};  // kd
    glm::vec3 specular{0.35f};               // ks
    float shininess = 48.0f;
    float reflectivity = 0.0f;  // 0: pure Blinn-Phong, 1: a mirror of the background
};

// `p` the hit, `d` the unit ray direction, `n` the unit outward normal.
inline glm::vec3 shade_surface(const SurfaceMaterial& m, std::span<const scene::Light> lights,
                               const scene::Background& background, glm::vec3 p, glm::vec3 d, glm::vec3 n) {
    using V = simd::V3<float>;
    auto v3 = [](glm::vec3 a) { return V{a.x, a.y, a.z}; };
    const V c = shade::blinn_phong<float>(lights, v3(p), v3(n), v3(-d), v3(m.ambient), v3(m.diffuse),
                                          v3(m.specular), m.shininess);
    glm::vec3 colour(c.x, c.y, c.z);
    if (m.reflectivity > 0.0f)
        colour = glm::mix(colour, shade::background_radiance(background, glm::reflect(d, n)), m.reflectivity);
    return colour;
}

}  // namespace tessera::march
