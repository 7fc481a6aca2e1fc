// The arithmetic the shading kernels are written in, once for both lane types: `float` (the
// scalar reference path, one pixel at a time) and simd::vfloat (kLanes pixels per operation).
// A kernel is a template over F that calls only what is defined here and in simd.h, so the
// two instantiations compute the same formula in the same order (the raster library builds
// with -ffp-contract=off, so float does not fuse where vfloat does not).
#pragma once
#include <bit>
#include <cmath>
#include <cstdint>

#include "raster/simd/simd.h"

namespace tessera::simd {

using simd::vfloat;
using simd::vmask;

// Scalar counterparts of simd.h, with the same NaN behaviour as the scalar back end.
inline float fma(float a, float b, float c) { return std::fma(a, b, c); }
inline float min(float a, float b) { return a < b ? a : b; }
inline float max(float a, float b) { return a > b ? a : b; }
inline float sqrt(float a) { return std::sqrt(a); }
inline float select(bool m, float a, float b) { return m ? a : b; }
inline bool both(bool a, bool b) { return a && b; }
inline bool either(bool a, bool b) { return a || b; }
inline vmask both(vmask a, vmask b) { return a & b; }
inline vmask either(vmask a, vmask b) { return a | b; }
inline bool any_lane(bool m) { return m; }
inline bool any_lane(vmask m) { return any(m); }

// x * 2^e for a normal x > 0 (x >= FLT_MIN), split into e = floor(log2 x) and a mantissa in
// [1, 2). A denormal x splits differently per back end (AVX-512's getexp/getmant normalise
// it, the bit fields below do not), so callers clamp their input first.
inline float exponent_of(float x, float& mantissa) {
    const uint32_t bits = std::bit_cast<uint32_t>(x);
    mantissa = std::bit_cast<float>((bits & 0x007FFFFFu) | 0x3F800000u);
    return float(int32_t(bits >> 23) - 127);
}
// 2^n for an integer-valued n in [-126, 127].
inline float exp2_int(float n) { return std::bit_cast<float>(uint32_t(int32_t(n) + 127) << 23); }
inline float floor_of(float x) { return std::floor(x); }

#if defined(__AVX512F__)
inline vfloat exponent_of(vfloat x, vfloat& mantissa) {
    // The zero-masking forms: GCC 12 warns about the unmasked ones' undefined pass-through.
    mantissa = _mm512_maskz_getmant_ps(0xFFFF, x.v, _MM_MANT_NORM_1_2, _MM_MANT_SIGN_src);
    return _mm512_maskz_getexp_ps(0xFFFF, x.v);
}
inline vfloat exp2_int(vfloat n) { return _mm512_maskz_scalef_ps(0xFFFF, _mm512_set1_ps(1.0f), n.v); }
inline simd::vint gather_int(const int32_t* base, simd::vint index) {
    return _mm512_mask_i32gather_epi32(_mm512_setzero_si512(), 0xFFFF, index.v, base, 4);
}
inline vfloat floor_of(vfloat x) { return _mm512_maskz_roundscale_ps(0xFFFF, x.v, _MM_FROUND_TO_NEG_INF); }
#elif defined(__AVX2__)
inline vfloat exponent_of(vfloat x, vfloat& mantissa) {
    const __m256i bits = _mm256_castps_si256(x.v);
    mantissa = _mm256_castsi256_ps(_mm256_or_si256(_mm256_and_si256(bits, _mm256_set1_epi32(0x007FFFFF)),
                                                   _mm256_set1_epi32(0x3F800000)));
    return _mm256_cvtepi32_ps(_mm256_sub_epi32(_mm256_srli_epi32(bits, 23), _mm256_set1_epi32(127)));
}
inline vfloat exp2_int(vfloat n) {
    const __m256i e = _mm256_add_epi32(_mm256_cvtps_epi32(n.v), _mm256_set1_epi32(127));
    return _mm256_castsi256_ps(_mm256_slli_epi32(e, 23));
}
inline vfloat floor_of(vfloat x) { return _mm256_floor_ps(x.v); }
inline simd::vint gather_int(const int32_t* base, simd::vint index) {
    return _mm256_i32gather_epi32(base, index.v, 4);
}
#else
inline vfloat exponent_of(vfloat x, vfloat& mantissa) {
    float m;
    const float e = exponent_of(x.v, m);
    mantissa = m;
    return e;
}
inline vfloat exp2_int(vfloat n) { return exp2_int(n.v); }
inline vfloat floor_of(vfloat x) { return std::floor(x.v); }
inline simd::vint gather_int(const int32_t* base, simd::vint index) { return base[index.v]; }
#endif

// std::max(a, b) and std::min(a, b) lane by lane, "a < b ? b : a" and "b < a ? b : a": for lane
// forms of scalar code written with them (the max/min instructions pick differently between
// zeros of opposite sign and around NaN).
template <class F>
F std_max(F a, F b) {
    return select(a < b, b, a);
}
template <class F>
F std_min(F a, F b) {
    return select(b < a, b, a);
}

template <class F>
F abs_of(F x) {
    return max(x, F(0.0f) - x);
}

// log2(x) for a normal x > 0 (see exponent_of): exponent plus log2 of the mantissa m in [1, 2)
// by the series log2 m = (2 / ln 2) atanh(t), t = (m - 1)/(m + 1) in [0, 1/3), to t^9. The
// first term left out, (2 / ln 2) t^11 / 11, makes the absolute error grow towards m = 2:
// < 2e-6 (1.84e-6 at m = 1.9993, over every float mantissa).
template <class F>
F log2_positive(F x) {
    F m;
    const F e = exponent_of(x, m);
    const F t = (m - F(1.0f)) / (m + F(1.0f));
    const F t2 = t * t;
    F s = fma(t2, F(1.0f / 9.0f), F(1.0f / 7.0f));
    s = fma(s, t2, F(1.0f / 5.0f));
    s = fma(s, t2, F(1.0f / 3.0f));
    s = fma(s, t2, F(1.0f));
    return fma(s * t, F(2.8853900817779268f), e);  // 2 / ln 2
}

// 2^y for y <= 0 (values below -126 give 0): 2^floor(y) times a degree-7 Taylor polynomial
// of 2^f = e^(f ln 2), f in [0, 1) (relative error < 1e-6: 7.9e-7 at most over 2^22 steps of f).
template <class F>
F exp2_nonpositive(F y) {
    const F yc = max(y, F(-126.0f));
    const F n = floor_of(yc);
    const F f = (yc - n) * F(0.69314718055994531f);
    F p = fma(f, F(1.0f / 5040.0f), F(1.0f / 720.0f));
    p = fma(p, f, F(1.0f / 120.0f));
    p = fma(p, f, F(1.0f / 24.0f));
    p = fma(p, f, F(1.0f / 6.0f));
    p = fma(p, f, F(0.5f));
    p = fma(p, f, F(1.0f));
    p = fma(p, f, F(1.0f));
    return select(y < F(-126.0f), F(0.0f), p * exp2_int(n));
}

// x^y for x in [0, 1] and y >= 0: the specular term cos(delta)^shine. 0^y = 0 for y > 0 and
// x^0 = 1 (OpenGL leaves 0^0 undefined; 1 is what GLSL implementations return).
template <class F>
F pow01(F x, F y) {
    const F safe = max(x, F(1e-30f));
    const F r = exp2_nonpositive(y * log2_positive(safe));
    return select(y <= F(0.0f), F(1.0f), select(x <= F(0.0f), F(0.0f), r));
}

// glm::smoothstep(edge0, edge1, x) with glm's operations in glm's order (its clamp is
// min(max(t, 0), 1) with glm's comparisons), so the float form is the value glm gives.
template <class F>
F smoothstep(float edge0, float edge1, F x) {
    F t = (x - F(edge0)) / F(edge1 - edge0);
    t = select(t < F(0.0f), F(0.0f), t);
    t = select(F(1.0f) < t, F(1.0f), t);
    return t * t * (F(3.0f) - F(2.0f) * t);
}

// e^x rounded once to float from a double-precision evaluation: x = n ln 2 + r, |r| <= ln 2 / 2
// (n rounded to nearest by the 1.5 * 2^52 shifter, which also leaves n in the low bits), e^r
// by its Taylor series to r^12 (truncation < 2e-16 relative), times 2^n made in the exponent
// field. The double is within about 1e-13 (relative) of e^x, so the float is the correctly
// rounded e^x except within that distance of a rounding tie. Every operation is IEEE double
// and branch-free, so a loop of it over lanes (which the compiler vectorises, four or eight
// doubles per instruction) gives the one-value call's bits at any lane width.
// For x in [-150, 100] or NaN (exp_of clamps first).
inline double exp_double_clamped(double x) {
    constexpr double kShifter = 6755399441055744.0;  // 1.5 * 2^52
    const double shifted = x * 1.4426950408889634 + kShifter;
    const double n = shifted - kShifter;
    const double r = (x - n * 0.6931471805599453) - n * 2.3190468138462996e-17;  // ln 2 in two parts
    double p = 1.0 / 479001600.0;
    p = p * r + 1.0 / 39916800.0;
    p = p * r + 1.0 / 3628800.0;
    p = p * r + 1.0 / 362880.0;
    p = p * r + 1.0 / 40320.0;
    p = p * r + 1.0 / 5040.0;
    p = p * r + 1.0 / 720.0;
    p = p * r + 1.0 / 120.0;
    p = p * r + 1.0 / 24.0;
    p = p * r + 1.0 / 6.0;
    p = p * r + 0.5;
    p = p * r + 1.0;
    p = p * r + 1.0;
    const uint64_t n_bits = std::bit_cast<uint64_t>(shifted) - std::bit_cast<uint64_t>(kShifter);
    return p * std::bit_cast<double>((n_bits + 1023u) << 52);
}

// e^-150 rounds to 0 and e^100 to infinity in float, as expf does; NaN stays NaN (the
// comparisons keep their second operand for it).
template <class F>
F exp_argument(F x) {
    return min(F(100.0f), max(F(-150.0f), x));
}

// e^x, and e^x - 1 for |x| >= 1e-4 (callers take a series below: the subtraction in double
// loses at most 14 of its 53 bits there, before the one rounding to float).
inline float exp_of(float x) { return float(exp_double_clamped(double(exp_argument(x)))); }
inline float expm1_of(float x) { return float(exp_double_clamped(double(exp_argument(x))) - 1.0); }
inline vfloat exp_of(vfloat x) {
    alignas(64) float lanes[kLanes];
    exp_argument(x).store(lanes);
    for (float& l : lanes) l = float(exp_double_clamped(double(l)));
    return vfloat::load(lanes);
}
inline vfloat expm1_of(vfloat x) {
    alignas(64) float lanes[kLanes];
    exp_argument(x).store(lanes);
    for (float& l : lanes) l = float(exp_double_clamped(double(l)) - 1.0);
    return vfloat::load(lanes);
}

template <class F>
struct V3 {
    F x, y, z;
};
template <class F>
V3<F> operator+(V3<F> a, V3<F> b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
template <class F>
V3<F> operator-(V3<F> a, V3<F> b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
template <class F>
V3<F> operator*(V3<F> a, F s) { return {a.x * s, a.y * s, a.z * s}; }
template <class F>
V3<F> operator*(V3<F> a, V3<F> b) { return {a.x * b.x, a.y * b.y, a.z * b.z}; }
template <class F>
F dot(V3<F> a, V3<F> b) { return fma(a.x, b.x, fma(a.y, b.y, a.z * b.z)); }
template <class F>
V3<F> cross(V3<F> a, V3<F> b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
template <class F, class M>
V3<F> select(M m, V3<F> a, V3<F> b) {
    return {select(m, a.x, b.x), select(m, a.y, b.y), select(m, a.z, b.z)};
}
// a * s + b, per component.
template <class F>
V3<F> madd(V3<F> a, F s, V3<F> b) { return {fma(a.x, s, b.x), fma(a.y, s, b.y), fma(a.z, s, b.z)}; }
// Unit vector along v, or `fallback` where v has zero (or non-finite) length.
template <class F>
V3<F> normalize_or(V3<F> v, V3<F> fallback) {
    const F len2 = dot(v, v);
    const auto ok = both(F(1e-30f) < len2, len2 < F(3.0e38f));
    const F inv = F(1.0f) / sqrt(select(ok, len2, F(1.0f)));
    return select(ok, v * inv, fallback);
}

}  // namespace tessera::simd
