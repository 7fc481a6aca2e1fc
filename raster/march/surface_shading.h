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

namespace surface_detail {
// The background along reflected directions: one (the reference) or kLanes at once, equal
// lane by lane (background_radiance.h).
inline simd::V3<float> environment(const scene::Background& background, simd::V3<float> r) {
    const glm::vec3 c = shade::background_radiance(background, glm::vec3(r.x, r.y, r.z));
    return {c.x, c.y, c.z};
}
inline simd::V3<simd::vfloat> environment(const scene::Background& background, simd::V3<simd::vfloat> r) {
    return shade::background_radiance_lanes(background, r);
}
}  // namespace surface_detail

// `p` the hit, `d` the unit ray direction, `n` the unit outward normal: one hit (F = float,
// the reference) or kLanes hits (F = simd::vfloat), with glm's arithmetic for reflect (I - N
// dot(N, I) 2, the dot summed x, y, z) and mix (x (1 - a) + y a), so both agree bit for bit.
template <class F>
simd::V3<F> shade_surface(const SurfaceMaterial& m, std::span<const scene::Light> lights,
                          const scene::Background& background, simd::V3<F> p, simd::V3<F> d, simd::V3<F> n) {
    using V = simd::V3<F>;
    auto v3 = [](glm::vec3 a) { return V{F(a.x), F(a.y), F(a.z)}; };
    const F minus(-1.0f);
    const V c = shade::blinn_phong<F>(lights, p, n, V{d.x * minus, d.y * minus, d.z * minus}, v3(m.ambient),
                                      v3(m.diffuse), v3(m.specular), F(m.shininess));
    if (!(m.reflectivity > 0.0f)) return c;
    const F along = (n.x * d.x + n.y * d.y) + n.z * d.z;
    const V reflected{d.x - n.x * along * F(2.0f), d.y - n.y * along * F(2.0f), d.z - n.z * along * F(2.0f)};
    const V env = surface_detail::environment(background, reflected);
    const F keep(1.0f - m.reflectivity), share(m.reflectivity);
    return {c.x * keep + env.x * share, c.y * keep + env.y * share, c.z * keep + env.z * share};
}

inline glm::vec3 shade_surface(const SurfaceMaterial& m, std::span<const scene::Light> lights,
                               const scene::Background& background, glm::vec3 p, glm::vec3 d, glm::vec3 n) {
    auto v3 = [](glm::vec3 a) { return simd::V3<float>{a.x, a.y, a.z}; };
    const simd::V3<float> c = shade_surface<float>(m, lights, background, v3(p), v3(d), v3(n));
    return {c.x, c.y, c.z};
}

}  // namespace tessera::march
