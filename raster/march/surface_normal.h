// Surface normals of an implicit field at a hit: the outward normal is
// -grad f / |grad f| (f > 0 inside), with grad f either the field's analytic gradient or the
// central differences
//   grad f ~ (f(p + h x) - f(p - h x), f(p + h y) - f(p - h y), f(p + h z) - f(p - h z)) / 2h
// with h = 0.05 usually. Differences cost six field evaluations and blur detail smaller
// than h; the analytic gradient costs one gradient evaluation and is exact.
#pragma once
#include <glm/glm.hpp>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "raster/march/march_field.h"
#include "raster/simd/lane_math.h"

namespace tessera::march {

enum class NormalMethod { analytic, central_differences };

struct NormalSettings {
    NormalMethod method = NormalMethod::analytic;
    float h = 0.05f;  // central-difference half step (0.05 is the usual choice)

    void validate() const {
        if (!(h > 0.0f) || !std::isfinite(h))
            throw std::invalid_argument("normals: central-difference step must be positive and finite, got " +
                                        std::to_string(h));
    }
};

template <MarchField F>
glm::vec3 central_difference_gradient(const F& field, glm::vec3 p, float h) {
    const glm::vec3 dx(h, 0.0f, 0.0f), dy(0.0f, h, 0.0f), dz(0.0f, 0.0f, h);
    return glm::vec3(field.value(p + dx) - field.value(p - dx),
                     field.value(p + dy) - field.value(p - dy),
                     field.value(p + dz) - field.value(p - dz)) /
           (2.0f * h);
}

// The unit outward normal at p; (0, 1, 0) where the gradient vanishes (a degenerate point
// has no direction, and "up" shades plausibly).
template <MarchField F>
glm::vec3 surface_normal(const F& field, glm::vec3 p, const NormalSettings& settings) {
    const glm::vec3 g = settings.method == NormalMethod::analytic
                            ? glm::vec3(field.gradient(p))
                            : central_difference_gradient(field, p, settings.h);
    const float len = glm::length(g);
    if (!(len > 0.0f) || !std::isfinite(len)) return {0.0f, 1.0f, 0.0f};
    return -g / len;
}

// surface_normal at kMarchLanes points (x[i], y[i], z[i]), equal to it lane by lane: the
// analytic gradient through the field's packet or batch form (evaluate_gradients), normalised
// in lanes with glm::length's and the division's order; central differences a lane at a time.
template <MarchField F>
simd::V3<simd::vfloat> surface_normals(const F& field, const float* x, const float* y, const float* z,
                                       const NormalSettings& settings) {
    using simd::vfloat;
    alignas(64) float gx[kMarchLanes], gy[kMarchLanes], gz[kMarchLanes];
    if (settings.method == NormalMethod::analytic) {
        evaluate_gradients(field, x, y, z, gx, gy, gz);
        const simd::V3<vfloat> g{vfloat::load(gx), vfloat::load(gy), vfloat::load(gz)};
        const vfloat len = simd::sqrt((g.x * g.x + g.y * g.y) + g.z * g.z);
        const simd::vmask usable = (vfloat(0.0f) < len) & (len < vfloat(std::numeric_limits<float>::infinity()));
        const vfloat minus(-1.0f);
        return simd::select(usable, simd::V3<vfloat>{g.x * minus / len, g.y * minus / len, g.z * minus / len},
                            simd::V3<vfloat>{vfloat(0.0f), vfloat(1.0f), vfloat(0.0f)});
    }
    for (int i = 0; i < kMarchLanes; ++i) {
        const glm::vec3 n = surface_normal(field, glm::vec3(x[i], y[i], z[i]), settings);
        gx[i] = n.x;
        gy[i] = n.y;
        gz[i] = n.z;
    }
    return {vfloat::load(gx), vfloat::load(gy), vfloat::load(gz)};
}

}  // namespace tessera::march
