// Fractal sums of noise with exact gradients: fBm, ridged multifractal and domain warping, each
// on an unbounded or a repeating (tileable) lattice. Each returns the value and its gradient
// by the chain rule (octave i is sampled at p * lacunarity^i, so its gradient is scaled by
// lacunarity^i; a warped field is multiplied by the warp's Jacobian).
#pragma once
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <cstdint>

#include "procedural/noise.h"

namespace tessera::procedural {

struct Fractal {
    int octaves = 6;
    float lacunarity = 2.0f;  // frequency ratio between octaves
    float gain = 0.5f;        // amplitude ratio between octaves (0.5: 1/f, "pink" spectrum)
    uint32_t seed = 0;
};

// Octave i's own seed, so octaves are independent and their lattices do not line up.
inline uint32_t octave_seed(uint32_t seed, int octave) {
    return seed + uint32_t(octave) * 0x9e3779b9u;
}

// Sum of amplitudes of the octaves, used to keep fBm in [-1, 1] whatever the octave count.
inline float fractal_amplitude(const Fractal& f) {
    float sum = 0.0f, amplitude = 1.0f;
    for (int i = 0; i < f.octaves; ++i, amplitude *= f.gain) sum += amplitude;
    return sum;
}

// Where the octaves' lattices live. OpenLattice: the unbounded plane. TorusLattice: a lattice
// that repeats every `period` cells, so a texture covering `period` cells of octave 0 wraps
// seamlessly; octave i is sampled at p * lacunarity^i, so with a whole-number lacunarity its
// lattice repeats every period * lacunarity^i of its own cells (finer()), the same distance in
// input units, and the whole sum wraps.
struct OpenLattice {
    // An octave's noise at p with its seed already avalanched (noise_detail::seed_key), so that
    // batch loops make the key once per octave; value() and gradient() are these with the seed.
    TESSERA_NOISE_INLINE Noise2 value_at(uint32_t key, glm::vec2 p) const {
        using namespace noise_detail;
        return value2(key, axis(p.x, kPrimeX), axis(p.y, kPrimeY));
    }
    TESSERA_NOISE_INLINE Noise2 gradient_at(uint32_t key, glm::vec2 p) const {
        using namespace noise_detail;
        return gradient2(key, axis(p.x, kPrimeX), axis(p.y, kPrimeY));
    }
    Noise2 value(glm::vec2 p, uint32_t seed) const { return value_at(noise_detail::seed_key(seed), p); }
    Noise2 gradient(glm::vec2 p, uint32_t seed) const { return gradient_at(noise_detail::seed_key(seed), p); }
    OpenLattice finer(int) const { return *this; }
};

struct TorusLattice {
    glm::ivec2 period;  // cells, > 0 on both axes
    TESSERA_NOISE_INLINE Noise2 value_at(uint32_t key, glm::vec2 p) const {
        using namespace noise_detail;
        return value2(key, periodic_axis(p.x, period.x, kPrimeX), periodic_axis(p.y, period.y, kPrimeY));
    }
    TESSERA_NOISE_INLINE Noise2 gradient_at(uint32_t key, glm::vec2 p) const {
        using namespace noise_detail;
        return gradient2(key, periodic_axis(p.x, period.x, kPrimeX), periodic_axis(p.y, period.y, kPrimeY));
    }
    Noise2 value(glm::vec2 p, uint32_t seed) const { return value_at(noise_detail::seed_key(seed), p); }
    Noise2 gradient(glm::vec2 p, uint32_t seed) const { return gradient_at(noise_detail::seed_key(seed), p); }
    TorusLattice finer(int lacunarity) const { return {period * lacunarity}; }
};

// One octave of each sum at one point: what the single-point functions below and the batch
// loops of fractal_batch.cpp both run, so a batch gives each point the single call's bits.
namespace fractal_detail {

// fBm: amplitude times the octave's noise; its gradient scaled by the chain rule.
template <class Noise>
TESSERA_NOISE_INLINE void fbm_octave(Noise& sum, Noise n, float amplitude, float frequency) {
    sum.value += amplitude * n.value;
    sum.gradient += (amplitude * frequency) * n.gradient;
}

// The ridged multifractal's running sum and the weight the next octave's signal gets.
struct RidgedSum {
    float value = 0.0f;
    float weight = 1.0f;
    glm::vec2 gradient{0.0f};
    glm::vec2 weight_gradient{0.0f};
};

TESSERA_NOISE_INLINE void ridged_octave(RidgedSum& s, Noise2 n, float amplitude, float frequency,
                                        float offset) {
    const float ridge = offset - (n.value < 0.0f ? -n.value : n.value);
    const glm::vec2 ridge_gradient = (n.value < 0.0f ? frequency : -frequency) * n.gradient;
    const float signal = ridge * ridge * s.weight;
    const glm::vec2 signal_gradient =
        (2.0f * ridge * s.weight) * ridge_gradient + (ridge * ridge) * s.weight_gradient;
    s.value += amplitude * signal;
    s.gradient += amplitude * signal_gradient;
    // Next weight = clamp(2 * signal, 0, 1); its gradient vanishes where it is clamped.
    const float w = 2.0f * signal;
    const bool inside = w > 0.0f && w < 1.0f;
    s.weight = w < 0.0f ? 0.0f : (w > 1.0f ? 1.0f : w);
    s.weight_gradient = inside ? 2.0f * signal_gradient : glm::vec2(0.0f);
}

// The domain warp's result from its three fBm: h at the warped point, and J^T grad h.
TESSERA_NOISE_INLINE Noise2 warp_chain(Noise2 h, Noise2 qx, Noise2 qy, float amount) {
    return {h.value, h.gradient + amount * (h.gradient.x * qx.gradient + h.gradient.y * qy.gradient)};
}

// The two fBm of a domain warp, independent of the warped one's.
inline Fractal warp_x(const Fractal& f) { return {f.octaves, f.lacunarity, f.gain, f.seed ^ 0x51ed270bu}; }
inline Fractal warp_y(const Fractal& f) { return {f.octaves, f.lacunarity, f.gain, f.seed ^ 0x2c1b3c6du}; }
// The offset of the second warp field's sample point (so the two are not the same field).
inline constexpr glm::vec2 kWarpYOffset{5.2f, 1.3f};

}  // namespace fractal_detail

// fBm of 2-D value noise, in [-1, 1], on the given lattice (a TorusLattice needs a whole-number
// lacunarity).
template <class Lattice>
TESSERA_NOISE_INLINE Noise2 fbm(glm::vec2 p, const Fractal& f, Lattice lattice) {
    Noise2 sum{0.0f, glm::vec2(0.0f)};
    float amplitude = 1.0f, frequency = 1.0f;
    for (int i = 0; i < f.octaves; ++i) {
        fractal_detail::fbm_octave(sum, lattice.value(p * frequency, octave_seed(f.seed, i)), amplitude, frequency);
        amplitude *= f.gain;
        frequency *= f.lacunarity;
        lattice = lattice.finer(int(f.lacunarity));
    }
    const float norm = 1.0f / fractal_amplitude(f);
    return {sum.value * norm, sum.gradient * norm};
}

TESSERA_NOISE_INLINE Noise2 fbm(glm::vec2 p, const Fractal& f) { return fbm(p, f, OpenLattice{}); }

// Tileable fBm: wraps every `period` octave-0 cells. The lacunarity must be a whole number.
TESSERA_NOISE_INLINE Noise2 fbm_periodic(glm::vec2 p, glm::ivec2 period, const Fractal& f) {
    return fbm(p, f, TorusLattice{period});
}

// fBm of 3-D value noise, in [-1, 1] (volumes with overhangs; fog density).
TESSERA_NOISE_INLINE Noise3 fbm(glm::vec3 p, const Fractal& f) {
    Noise3 sum{0.0f, glm::vec3(0.0f)};
    float amplitude = 1.0f, frequency = 1.0f;
    for (int i = 0; i < f.octaves; ++i) {
        fractal_detail::fbm_octave(sum, value_noise(p * frequency, octave_seed(f.seed, i)), amplitude, frequency);
        amplitude *= f.gain;
        frequency *= f.lacunarity;
    }
    const float norm = 1.0f / fractal_amplitude(f);
    return {sum.value * norm, sum.gradient * norm};
}

// Ridged multifractal (Musgrave): each octave is (offset - |noise|)^2, weighted by the previous
// octave's signal so that ridges get sharp detail and valleys stay smooth. In [0, 1] for
// offset = 1. It folds gradient noise: the zero lines of value noise run along the lattice axes
// and would make the ridges a grid. The gradient carries the weight's dependence on the previous octave; it is
// undefined exactly on a crest (|noise| = 0), like the surface's own crease. Each octave's ridge
// depends only on that octave's noise at the point, so on a TorusLattice the sum wraps too.
template <class Lattice>
TESSERA_NOISE_INLINE Noise2 ridged(glm::vec2 p, const Fractal& f, Lattice lattice, float offset = 1.0f) {
    fractal_detail::RidgedSum sum;
    float amplitude = 1.0f, frequency = 1.0f;
    for (int i = 0; i < f.octaves; ++i) {
        fractal_detail::ridged_octave(sum, lattice.gradient(p * frequency, octave_seed(f.seed, i)), amplitude,
                                      frequency, offset);
        amplitude *= f.gain;
        frequency *= f.lacunarity;
        lattice = lattice.finer(int(f.lacunarity));
    }
    const float norm = 1.0f / fractal_amplitude(f);
    return {sum.value * norm, sum.gradient * norm};
}

TESSERA_NOISE_INLINE Noise2 ridged(glm::vec2 p, const Fractal& f, float offset = 1.0f) {
    return ridged(p, f, OpenLattice{}, offset);
}

// Domain warping (Quilez, "warp"): h(p) = fbm(p + amount * q(p)) with q two independent fBm
// fields. The gradient is J^T grad h, J = I + amount * dq/dp. On a TorusLattice q and h both
// wrap, so p + period lands on the same warped point plus a period: the warp wraps too.
template <class Lattice>
TESSERA_NOISE_INLINE Noise2 domain_warp(glm::vec2 p, const Fractal& f, float amount, Lattice lattice) {
    using namespace fractal_detail;
    const Noise2 qx = fbm(p, warp_x(f), lattice);
    const Noise2 qy = fbm(p + kWarpYOffset, warp_y(f), lattice);
    const Noise2 h = fbm(p + amount * glm::vec2(qx.value, qy.value), f, lattice);
    return warp_chain(h, qx, qy, amount);
}

TESSERA_NOISE_INLINE Noise2 domain_warp(glm::vec2 p, const Fractal& f, float amount) {
    return domain_warp(p, f, amount, OpenLattice{});
}

}  // namespace tessera::procedural
