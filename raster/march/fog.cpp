#include "raster/march/fog.h"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace tessera::march {

namespace {

bool finite(glm::vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

std::string text(glm::vec3 v) {
    return "(" + std::to_string(v.x) + ", " + std::to_string(v.y) + ", " + std::to_string(v.z) + ")";
}

constexpr float kInfinity = std::numeric_limits<float>::infinity();

}  // namespace

void Fog::validate() const {
    if (!finite(density) || !(density.x >= 0.0f && density.y >= 0.0f && density.z >= 0.0f))
        throw std::invalid_argument("fog: density must be finite and non-negative, got " + text(density));
    if (!finite(colour))
        throw std::invalid_argument("fog: colour must be finite, got " + text(colour));
    if (!std::isfinite(falloff) || !(falloff >= 0.0f))
        throw std::invalid_argument("fog: height falloff must be finite and non-negative, got " +
                                    std::to_string(falloff));
    if (!std::isfinite(base_height))
        throw std::invalid_argument("fog: base height must be finite");
}

float Fog::unit_optical_depth(float origin_y, float direction_y, float distance) const {
    if (!(distance > 0.0f)) return 0.0f;
    if (falloff == 0.0f) return distance;  // constant density: tau / density = D
    const float at_eye = simd::exp_of(-falloff * (origin_y - base_height));
    if (std::isinf(distance)) {
        // Upward rays leave the fog with a finite integral; level or downward ones never do.
        return direction_y > 0.0f ? at_eye / (falloff * direction_y) : kInfinity;
    }
    const float x = falloff * direction_y * distance;
    const float shape = std::fabs(x) < 1e-4f ? 1.0f - x * (0.5f - x * (1.0f / 6.0f))
                                             : -simd::expm1_of(-x) / x;
    return at_eye * distance * shape;
}

glm::vec3 Fog::transmittance(glm::vec3 origin, glm::vec3 direction, float distance) const {
    const float unit = unit_optical_depth(origin.y, direction.y, distance);
    // A channel without fog stays clear even at infinite depth (0 * inf would be NaN).
    auto channel = [unit](float sigma) { return sigma > 0.0f ? simd::exp_of(-sigma * unit) : 1.0f; };
    return {channel(density.x), channel(density.y), channel(density.z)};
}

simd::V3<simd::vfloat> Fog::transmittance(glm::vec3 origin, simd::vfloat direction_y, simd::vfloat distance) const {
    using simd::vfloat;
    const vfloat inf(kInfinity), zero(0.0f);
    // unit_optical_depth with its choices as selects; lanes not taken may hold non-finite
    // values, which are never selected.
    vfloat unit = distance;
    if (falloff != 0.0f) {
        const float at_eye = simd::exp_of(-falloff * (origin.y - base_height));
        const vfloat x = vfloat(falloff) * direction_y * distance;
        const vfloat series = vfloat(1.0f) - x * (vfloat(0.5f) - x * vfloat(1.0f / 6.0f));
        const vfloat shape = simd::select(simd::abs_of(x) < vfloat(1e-4f), series,
                                          (zero - simd::expm1_of(zero - x)) / x);
        const vfloat upward = simd::select(zero < direction_y, vfloat(at_eye) / (vfloat(falloff) * direction_y), inf);
        unit = simd::select(inf <= distance, upward, vfloat(at_eye) * distance * shape);
    }
    unit = simd::select(zero < distance, unit, zero);
    auto channel = [&](float sigma) { return sigma > 0.0f ? simd::exp_of(vfloat(-sigma) * unit) : vfloat(1.0f); };
    return {channel(density.x), channel(density.y), channel(density.z)};
}

}  // namespace tessera::march
