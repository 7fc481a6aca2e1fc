// The illumination formulas (Blinn-Phong, toon), over one pixel (F = float) or kLanes pixels
// (F = simd::vfloat). Vectors are world-space; N, V, L are unit length.
#pragma once
#include <glm/glm.hpp>

#include <span>

#include "raster/scene/light.h"
#include "raster/simd/lane_math.h"

namespace tessera::shade {

// Written once in the lane arithmetic of simd/lane_math.h, for float and simd::vfloat.
using namespace simd;

template <class F>
V3<F> broadcast(glm::vec3 v) {
    return {F(v.x), F(v.y), F(v.z)};
}

// Unit vector from surface point p towards the light: wLiPos.xyz - p * wLiPos.w.
template <class F>
V3<F> light_direction(const scene::Light& light, V3<F> p, V3<F> fallback) {
    const V3<F> to = broadcast<F>(glm::vec3(light.position)) - p * F(light.position.w);
    return normalize_or(to, fallback);
}

// Blinn-Phong summed over the lights, exactly
//     L = ka*La + (kd*cos(theta) + ks*cos(delta)^shine) * Le,
// cos(theta) = max(N.L, 0), cos(delta) = max(N.H, 0), H = |L + V|.
template <class F>
V3<F> blinn_phong(std::span<const scene::Light> lights, V3<F> p, V3<F> n, V3<F> v, V3<F> ka, V3<F> kd,
                  V3<F> ks, F shine) {
    V3<F> sum{F(0.0f), F(0.0f), F(0.0f)};
    for (const scene::Light& light : lights) {
        const V3<F> l = light_direction<F>(light, p, n);
        const V3<F> h = normalize_or(l + v, n);
        const F cost = max(dot(n, l), F(0.0f));
        const F cosd = max(dot(n, h), F(0.0f));
        const F spec = pow01(cosd, shine);
        const V3<F> reflected = madd(kd, cost, ks * spec);
        sum = sum + ka * broadcast<F>(light.La) + reflected * broadcast<F>(light.Le);
    }
    return sum;
}

// The NPR (toon) shader: y = dot(N, L) > 0.5 ? 1 : 0.5 and colour y * kd, black where
// |dot(N, V)| < 0.2 (the silhouette). With several lights the levels add, weighted by Le
// (one white light gives the classic picture).
template <class F>
V3<F> toon(std::span<const scene::Light> lights, V3<F> p, V3<F> n, V3<F> v, V3<F> kd) {
    V3<F> sum{F(0.0f), F(0.0f), F(0.0f)};
    for (const scene::Light& light : lights) {
        const V3<F> l = light_direction<F>(light, p, n);
        const F y = select(F(0.5f) < dot(n, l), F(1.0f), F(0.5f));
        sum = sum + kd * broadcast<F>(light.Le) * y;
    }
    const auto silhouette = abs_of(dot(n, v)) < F(0.2f);
    return select(silhouette, V3<F>{F(0.0f), F(0.0f), F(0.0f)}, sum);
}

}  // namespace tessera::shade
