// Radial metaball kernels (seeds/003 homework: Blinn, Perlin, Wyvill), each written in
// s = r^2 / R^2 with R the support radius, so the sum needs no square root where the kernel
// does not, and the gradient is  grad K = dK/ds * 2 (p - c) / R^2  for every kernel.
//
// - Wyvill "soft objects": K = 1 - 22/9 s + 17/9 s^2 - 4/9 s^3 for s <= 1, else 0.
//   K(0) = 1, K(R/2) = 1/2, K(R) = 0, K'(R) = 0.
// - Perlin: the quintic fade on t = r/R, K = 1 - (6 t^5 - 15 t^4 + 10 t^3); in s,
//   dK/ds = dK/dt / (2t) = -15 t (1 - t)^2, finite at the centre. C2 at 0 and R.
// - Blinn "blobby": K = exp(-a s), infinite support. To let far balls be culled like the
//   others it is truncated at R, less its tangent line at the cut so that value and slope
//   both reach 0 there (C1, like Wyvill's):
//   K = (exp(-a s) - e (1 + a (1 - s))) / (1 - e (1 + a)), e = exp(-a), for s < 1, else 0.
//   The default sharpness a = ln 1000 puts the cut where the untruncated tail is 1/1000 of
//   the peak, so the correction is below 1 % of the kernel anywhere.
#pragma once
#include <cmath>

namespace tessera::march {

enum class MetaballKernel { blinn, perlin, wyvill };

struct KernelSample {
    float value;
    float d_ds;  // dK/ds
};

struct WyvillKernel {
    static KernelSample at(float s) {
        if (s >= 1.0f) return {0.0f, 0.0f};
        constexpr float a = -4.0f / 9.0f, b = 17.0f / 9.0f, c = -22.0f / 9.0f;
        return {1.0f + s * (c + s * (b + s * a)), c + s * (2.0f * b + s * 3.0f * a)};
    }
};

struct PerlinKernel {
    static KernelSample at(float s) {
        if (s >= 1.0f) return {0.0f, 0.0f};
        const float t = std::sqrt(s);
        const float fade = t * t * t * (10.0f + t * (-15.0f + t * 6.0f));
        const float u = 1.0f - t;
        return {1.0f - fade, -15.0f * t * u * u};
    }
};

// Holds the precomputed cut correction and scale of the truncated exponential.
struct BlinnKernel {
    float sharpness;
    float tail;   // exp(-a), the value at the cut
    float scale;  // 1 / (1 - exp(-a) (1 + a))

    explicit BlinnKernel(float a)
        : sharpness(a), tail(std::exp(-a)), scale(1.0f / (1.0f - std::exp(-a) * (1.0f + a))) {}

    KernelSample at(float s) const {
        if (s >= 1.0f) return {0.0f, 0.0f};
        const float e = std::exp(-sharpness * s);
        return {(e - tail * (1.0f + sharpness * (1.0f - s))) * scale,
                -sharpness * (e - tail) * scale};
    }
};

}  // namespace tessera::march
