// Radial metaball kernels (Blinn, Perlin, Wyvill), each written in
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
//
// Each kernel is written once over F = float (the scalar reference) and F = simd::vfloat (a
// packet of points), with the arithmetic of raster/simd/lane_math.h, so both compute the same
// formula in the same order; the exponential is simd::exp2_nonpositive (relative error
// below 1e-6), which vectorises where std::exp would not.
#pragma once
#include "raster/simd/lane_math.h"
#include "raster/simd/simd.h"

namespace tessera::march {

// select / sqrt / min below resolve to shade's float overloads or, by argument-dependent
// lookup, to simd's vfloat ones.
using simd::min;
using simd::select;
using simd::sqrt;

enum class MetaballKernel { blinn, perlin, wyvill };

template <class F>
struct KernelSample {
    F value;
    F d_ds;  // dK/ds
};

struct WyvillKernel {
    template <class F>
    static KernelSample<F> at(F s) {
        const F a(-4.0f / 9.0f), b(17.0f / 9.0f), c(-22.0f / 9.0f);
        const F two_b(2.0f * 17.0f / 9.0f), three_a(3.0f * -4.0f / 9.0f);
        const auto inside = s < F(1.0f);
        return {select(inside, F(1.0f) + s * (c + s * (b + s * a)), F(0.0f)),
                select(inside, c + s * (two_b + s * three_a), F(0.0f))};
    }
};

struct PerlinKernel {
    template <class F>
    static KernelSample<F> at(F s) {
        const auto inside = s < F(1.0f);
        const F t = sqrt(min(s, F(1.0f)));
        const F fade = t * t * t * (F(10.0f) + t * (F(-15.0f) + t * F(6.0f)));
        const F u = F(1.0f) - t;
        return {select(inside, F(1.0f) - fade, F(0.0f)),
                select(inside, F(-15.0f) * t * u * u, F(0.0f))};
    }
};

// Holds the precomputed cut correction and scale of the truncated exponential.
struct BlinnKernel {
    float sharpness;
    float tail;   // exp(-a), the value at the cut
    float scale;  // 1 / (1 - exp(-a) (1 + a))

    explicit BlinnKernel(float a)
        : sharpness(a),
          tail(simd::exp2_nonpositive(-a * 1.44269504088896341f)),
          scale(1.0f / (1.0f - tail * (1.0f + a))) {}

    template <class F>
    KernelSample<F> at(F s) const {
        const auto inside = s < F(1.0f);
        // e^{-a s} = 2^{-a s log2 e}; s >= 0 keeps the argument non-positive.
        const F e = simd::exp2_nonpositive(F(-sharpness * 1.44269504088896341f) * s);
        const F value = (e - F(tail) * (F(1.0f) + F(sharpness) * (F(1.0f) - s))) * F(scale);
        return {select(inside, value, F(0.0f)),
                select(inside, F(-sharpness) * (e - F(tail)) * F(scale), F(0.0f))};
    }
};

}  // namespace tessera::march
