// Lattice noise with analytic derivatives: value noise and gradient (Perlin-style) noise in 2-D
// and 3-D. Each call returns the value and its exact gradient, so terrain normals and ray-march
// shading never need finite differences (Inigo Quilez, "gradient noise derivatives" and
// "value noise derivatives": interpolate with the quintic fade u = 6t^5 - 15t^4 + 10t^3, whose
// derivative 30t^2(t-1)^2 is continuous, and differentiate the blend in closed form).
//
// The functions are inline and branch-free so that loops over many points (noise_batch.cpp,
// the heightfield rows) vectorise; a single call is the scalar reference for those loops.
// Every lattice value comes from mix32 (hash.h) of the seed and the corner coordinates: the same
// seed gives the same noise on every machine and thread count.
#pragma once
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <cstddef>
#include <cstdint>

#include "procedural/hash.h"
#include "procedural/simd_math.h"

// The noise functions are large; batch loops vectorise only when they are inlined.
#if defined(__GNUC__)
#define TESSERA_NOISE_INLINE inline __attribute__((always_inline))
#else
#define TESSERA_NOISE_INLINE inline
#endif

namespace tessera::procedural {

struct Noise2 {
    float value;
    glm::vec2 gradient;  // (d value/dx, d value/dy)
};

struct Noise3 {
    float value;
    glm::vec3 gradient;  // (d value/dx, d value/dy, d value/dz)
};

namespace noise_detail {

// Odd multipliers that spread lattice coordinates over all 32 bits before the avalanche mix;
// one xor per axis per corner keeps the 8 corner hashes of a 3-D cell cheap (the x products of
// the two corners differ by one add).
inline constexpr uint32_t kPrimeX = 0x8da6b343u;
inline constexpr uint32_t kPrimeY = 0xd8163841u;
inline constexpr uint32_t kPrimeZ = 0xcb1ab31fu;

// The seed is avalanched once per call (loop-invariant in batch loops).
inline uint32_t seed_key(uint32_t seed) { return mix32(seed ^ 0x9e3779b9u); }

// A lattice value in [-1, 1): the hash read as a signed 32-bit fraction.
inline float signed_unit(uint32_t h) { return float(int32_t(h)) * (1.0f / 2147483648.0f); }

// Quintic fade and its derivative (C2-continuous noise, so second derivatives are continuous
// and lighting on a noise surface shows no grid creases).
inline float fade(float t) { return t * t * t * (t * (t * 6.0f - 15.0f) + 10.0f); }
inline float fade_derivative(float t) {
    const float s = t * (t - 1.0f);
    return 30.0f * s * s;
}

// One axis of a lattice lookup: the cell's integer corner (times its multiplier), the next
// corner's, the fraction inside the cell. With a period > 0 the lattice repeats every `period`
// cells (the noise tiles); the coordinate may lie anywhere.
struct Axis {
    uint32_t h0, h1;
    float t;
};

inline Axis axis(float x, uint32_t prime) {
    const int32_t cell = floor_int(x);
    const uint32_t i = uint32_t(cell);
    return {i * prime, (i + 1u) * prime, x - float(cell)};
}

inline Axis periodic_axis(float x, int period, uint32_t prime) {
    const int32_t cell = floor_int(x);
    // cell mod period without integer division (none in SIMD): the quotient in float, then
    // one correction each way so that its rounding can never leave [0, period).
    int32_t i = cell - floor_int(float(cell) / float(period)) * period;
    i -= period * int32_t(i >= period);
    i += period * int32_t(i < 0);
    const int32_t next = (i + 1) * int32_t(i + 1 != period);
    return {uint32_t(i) * prime, uint32_t(next) * prime, x - float(cell)};
}

TESSERA_NOISE_INLINE Noise2 value2(uint32_t key, Axis x, Axis y) {
    const float a = signed_unit(mix32(key ^ x.h0 ^ y.h0));
    const float b = signed_unit(mix32(key ^ x.h1 ^ y.h0));
    const float c = signed_unit(mix32(key ^ x.h0 ^ y.h1));
    const float d = signed_unit(mix32(key ^ x.h1 ^ y.h1));
    const float ux = fade(x.t), uy = fade(y.t);
    const float k1 = b - a, k2 = c - a, k3 = a - b - c + d;
    return {a + k1 * ux + k2 * uy + k3 * ux * uy,
            {fade_derivative(x.t) * (k1 + k3 * uy), fade_derivative(y.t) * (k2 + k3 * ux)}};
}

// A pseudo-random corner gradient with components in [-1, 1) from disjoint bit fields.
inline glm::vec2 gradient2_at(uint32_t h) {
    return {float(int32_t(h) >> 16) * (1.0f / 32768.0f),
            float(int32_t(h << 16) >> 16) * (1.0f / 32768.0f)};
}
inline glm::vec3 gradient3_at(uint32_t h) {
    return {float(int32_t(h) >> 22) * (1.0f / 512.0f),
            float(int32_t(h << 10) >> 22) * (1.0f / 512.0f),
            float(int32_t(h << 20) >> 22) * (1.0f / 512.0f)};
}

TESSERA_NOISE_INLINE Noise2 gradient2(uint32_t key, Axis x, Axis y) {
    const glm::vec2 ga = gradient2_at(mix32(key ^ x.h0 ^ y.h0));
    const glm::vec2 gb = gradient2_at(mix32(key ^ x.h1 ^ y.h0));
    const glm::vec2 gc = gradient2_at(mix32(key ^ x.h0 ^ y.h1));
    const glm::vec2 gd = gradient2_at(mix32(key ^ x.h1 ^ y.h1));
    const float tx = x.t, ty = y.t;
    const float va = ga.x * tx + ga.y * ty;
    const float vb = gb.x * (tx - 1.0f) + gb.y * ty;
    const float vc = gc.x * tx + gc.y * (ty - 1.0f);
    const float vd = gd.x * (tx - 1.0f) + gd.y * (ty - 1.0f);
    const float ux = fade(tx), uy = fade(ty);
    const float k1 = vb - va, k2 = vc - va, k3 = va - vb - vc + vd;
    const glm::vec2 g = ga + ux * (gb - ga) + uy * (gc - ga) + ux * uy * (ga - gb - gc + gd);
    return {va + k1 * ux + k2 * uy + k3 * ux * uy,
            {g.x + fade_derivative(tx) * (k1 + k3 * uy), g.y + fade_derivative(ty) * (k2 + k3 * ux)}};
}

// Trilinear blend of the eight corner values a..h (a = (0,0,0), b = (1,0,0), c = (0,1,0),
// d = (1,1,0), e = (0,0,1), f = (1,0,1), g = (0,1,1), h = (1,1,1)) through the fade, and the
// blend's derivative with respect to the cell fractions.
struct Blend3 {
    float value;
    glm::vec3 derivative;
};
TESSERA_NOISE_INLINE Blend3 blend3(float a, float b, float c, float d, float e, float f, float g, float h,
                     glm::vec3 u, glm::vec3 du) {
    const float k1 = b - a, k2 = c - a, k3 = e - a;
    const float k4 = a - b - c + d, k5 = a - c - e + g, k6 = a - b - e + f;
    const float k7 = -a + b + c - d + e - f - g + h;
    return {a + k1 * u.x + k2 * u.y + k3 * u.z + k4 * u.x * u.y + k5 * u.y * u.z +
                k6 * u.z * u.x + k7 * u.x * u.y * u.z,
            {du.x * (k1 + k4 * u.y + k6 * u.z + k7 * u.y * u.z),
             du.y * (k2 + k5 * u.z + k4 * u.x + k7 * u.z * u.x),
             du.z * (k3 + k6 * u.x + k5 * u.y + k7 * u.x * u.y)}};
}

}  // namespace noise_detail

// 2-D value noise in [-1, 1] (one random value per lattice point, quintic interpolation).
inline Noise2 value_noise(glm::vec2 p, uint32_t seed) {
    using namespace noise_detail;
    return value2(seed_key(seed), axis(p.x, kPrimeX), axis(p.y, kPrimeY));
}

// As value_noise, with a lattice that repeats every period.x by period.y cells (> 0), so a
// texture covering whole periods tiles seamlessly.
inline Noise2 value_noise_periodic(glm::vec2 p, glm::ivec2 period, uint32_t seed) {
    using namespace noise_detail;
    return value2(seed_key(seed), periodic_axis(p.x, period.x, kPrimeX),
                  periodic_axis(p.y, period.y, kPrimeY));
}

// 2-D gradient (Perlin-style) noise, about [-1, 1]: zero at lattice points, random slopes.
inline Noise2 gradient_noise(glm::vec2 p, uint32_t seed) {
    using namespace noise_detail;
    return gradient2(seed_key(seed), axis(p.x, kPrimeX), axis(p.y, kPrimeY));
}

inline Noise2 gradient_noise_periodic(glm::vec2 p, glm::ivec2 period, uint32_t seed) {
    using namespace noise_detail;
    return gradient2(seed_key(seed), periodic_axis(p.x, period.x, kPrimeX),
                     periodic_axis(p.y, period.y, kPrimeY));
}

// 3-D value noise in [-1, 1] with its gradient (what a ray marcher shades with).
TESSERA_NOISE_INLINE Noise3 value_noise(glm::vec3 p, uint32_t seed) {
    using namespace noise_detail;
    const uint32_t key = seed_key(seed);
    const Axis x = axis(p.x, kPrimeX), y = axis(p.y, kPrimeY), z = axis(p.z, kPrimeZ);
    auto v = [key](uint32_t hx, uint32_t hy, uint32_t hz) {
        return signed_unit(mix32(key ^ hx ^ hy ^ hz));
    };
    const Blend3 r = blend3(v(x.h0, y.h0, z.h0), v(x.h1, y.h0, z.h0), v(x.h0, y.h1, z.h0),
                            v(x.h1, y.h1, z.h0), v(x.h0, y.h0, z.h1), v(x.h1, y.h0, z.h1),
                            v(x.h0, y.h1, z.h1), v(x.h1, y.h1, z.h1),
                            {fade(x.t), fade(y.t), fade(z.t)},
                            {fade_derivative(x.t), fade_derivative(y.t), fade_derivative(z.t)});
    return {r.value, r.derivative};
}

// 3-D gradient (Perlin-style) noise, about [-1, 1], with its gradient.
TESSERA_NOISE_INLINE Noise3 gradient_noise(glm::vec3 p, uint32_t seed) {
    using namespace noise_detail;
    const uint32_t key = seed_key(seed);
    const Axis x = axis(p.x, kPrimeX), y = axis(p.y, kPrimeY), z = axis(p.z, kPrimeZ);
    const glm::vec3 t{x.t, y.t, z.t};
    auto g = [key](uint32_t hx, uint32_t hy, uint32_t hz) {
        return gradient3_at(mix32(key ^ hx ^ hy ^ hz));
    };
    const glm::vec3 ga = g(x.h0, y.h0, z.h0), gb = g(x.h1, y.h0, z.h0);
    const glm::vec3 gc = g(x.h0, y.h1, z.h0), gd = g(x.h1, y.h1, z.h0);
    const glm::vec3 ge = g(x.h0, y.h0, z.h1), gf = g(x.h1, y.h0, z.h1);
    const glm::vec3 gg = g(x.h0, y.h1, z.h1), gh = g(x.h1, y.h1, z.h1);
    auto dot = [](glm::vec3 a, glm::vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; };
    const float va = dot(ga, t), vb = dot(gb, t - glm::vec3(1, 0, 0));
    const float vc = dot(gc, t - glm::vec3(0, 1, 0)), vd = dot(gd, t - glm::vec3(1, 1, 0));
    const float ve = dot(ge, t - glm::vec3(0, 0, 1)), vf = dot(gf, t - glm::vec3(1, 0, 1));
    const float vg = dot(gg, t - glm::vec3(0, 1, 1)), vh = dot(gh, t - glm::vec3(1, 1, 1));
    const glm::vec3 u{fade(t.x), fade(t.y), fade(t.z)};
    const Blend3 r = blend3(va, vb, vc, vd, ve, vf, vg, vh, u,
                            {fade_derivative(t.x), fade_derivative(t.y), fade_derivative(t.z)});
    // d/dp of the blended corner values also carries the blended corner gradients.
    const glm::vec3 blended = ga + u.x * (gb - ga) + u.y * (gc - ga) + u.z * (ge - ga) +
                              u.x * u.y * (ga - gb - gc + gd) + u.y * u.z * (ga - gc - ge + gg) +
                              u.z * u.x * (ga - gb - ge + gf) +
                              u.x * u.y * u.z * (-ga + gb + gc - gd + ge - gf - gg + gh);
    return {r.value, r.derivative + blended};
}

// Batch forms over n points in structure-of-arrays layout (SIMD over points); out[i] equals the
// single call at point i, bit for bit. With dx, dy and dz null (all three) only the values are
// computed; the choice is made once per call, so the point loop stays branch-free.
void value_noise_batch(uint32_t seed, size_t n, const float* x, const float* y, const float* z,
                       float* value, float* dx = nullptr, float* dy = nullptr, float* dz = nullptr);
void gradient_noise_batch(uint32_t seed, size_t n, const float* x, const float* y, const float* z,
                          float* value, float* dx = nullptr, float* dy = nullptr, float* dz = nullptr);

}  // namespace tessera::procedural
