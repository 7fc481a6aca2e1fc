// Fractal sums of noise with exact gradients: fBm, ridged multifractal, domain warping, and the
// anisotropic dune relief for the snake scene's sand. Each returns the value and its gradient
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

// fBm of 2-D value noise, in [-1, 1].
TESSERA_NOISE_INLINE Noise2 fbm(glm::vec2 p, const Fractal& f) {
    float value = 0.0f, amplitude = 1.0f, frequency = 1.0f;
    glm::vec2 gradient(0.0f);
    for (int i = 0; i < f.octaves; ++i) {
        const Noise2 n = value_noise(p * frequency, octave_seed(f.seed, i));
        value += amplitude * n.value;
        gradient += (amplitude * frequency) * n.gradient;
        amplitude *= f.gain;
        frequency *= f.lacunarity;
    }
    const float norm = 1.0f / fractal_amplitude(f);
    return {value * norm, gradient * norm};
}

// Tileable fBm: octave i's lattice repeats every period * lacunarity^i cells, so a texture that
// covers `period` cells of octave 0 wraps seamlessly. The lacunarity must be a whole number.
TESSERA_NOISE_INLINE Noise2 fbm_periodic(glm::vec2 p, glm::ivec2 period, const Fractal& f) {
    float value = 0.0f, amplitude = 1.0f, frequency = 1.0f;
    glm::vec2 gradient(0.0f);
    const int lacunarity = int(f.lacunarity);
    for (int i = 0; i < f.octaves; ++i) {
        const Noise2 n = value_noise_periodic(p * frequency, period, octave_seed(f.seed, i));
        value += amplitude * n.value;
        gradient += (amplitude * frequency) * n.gradient;
        amplitude *= f.gain;
        frequency *= float(lacunarity);
        period *= lacunarity;
    }
    const float norm = 1.0f / fractal_amplitude(f);
    return {value * norm, gradient * norm};
}

// fBm of 3-D value noise, in [-1, 1] (volumes with overhangs; fog density).
TESSERA_NOISE_INLINE Noise3 fbm(glm::vec3 p, const Fractal& f) {
    float value = 0.0f, amplitude = 1.0f, frequency = 1.0f;
    glm::vec3 gradient(0.0f);
    for (int i = 0; i < f.octaves; ++i) {
        const Noise3 n = value_noise(p * frequency, octave_seed(f.seed, i));
        value += amplitude * n.value;
        gradient += (amplitude * frequency) * n.gradient;
        amplitude *= f.gain;
        frequency *= f.lacunarity;
    }
    const float norm = 1.0f / fractal_amplitude(f);
    return {value * norm, gradient * norm};
}

// Ridged multifractal (Musgrave): each octave is (offset - |noise|)^2, weighted by the previous
// octave's signal so that ridges get sharp detail and valleys stay smooth. In [0, 1] for
// offset = 1. It folds gradient noise: the zero lines of value noise run along the lattice axes
// and would make the ridges a grid. The gradient carries the weight's dependence on the previous octave; it is
// undefined exactly on a crest (|noise| = 0), like the surface's own crease.
TESSERA_NOISE_INLINE Noise2 ridged(glm::vec2 p, const Fractal& f, float offset = 1.0f) {
    float value = 0.0f, amplitude = 1.0f, frequency = 1.0f;
    float weight = 1.0f;
    glm::vec2 gradient(0.0f), weight_gradient(0.0f);
    for (int i = 0; i < f.octaves; ++i) {
        const Noise2 n = gradient_noise(p * frequency, octave_seed(f.seed, i));
        const float ridge = offset - (n.value < 0.0f ? -n.value : n.value);
        const glm::vec2 ridge_gradient = (n.value < 0.0f ? frequency : -frequency) * n.gradient;
        const float signal = ridge * ridge * weight;
        const glm::vec2 signal_gradient =
            (2.0f * ridge * weight) * ridge_gradient + (ridge * ridge) * weight_gradient;
        value += amplitude * signal;
        gradient += amplitude * signal_gradient;
        // Next weight = clamp(2 * signal, 0, 1); its gradient vanishes where it is clamped.
        const float w = 2.0f * signal;
        const bool inside = w > 0.0f && w < 1.0f;
        weight = w < 0.0f ? 0.0f : (w > 1.0f ? 1.0f : w);
        weight_gradient = inside ? 2.0f * signal_gradient : glm::vec2(0.0f);
        amplitude *= f.gain;
        frequency *= f.lacunarity;
    }
    const float norm = 1.0f / fractal_amplitude(f);
    return {value * norm, gradient * norm};
}

// Domain warping (Quilez, "warp"): h(p) = fbm(p + amount * q(p)) with q two independent fBm
// fields. The gradient is J^T grad h, J = I + amount * dq/dp.
TESSERA_NOISE_INLINE Noise2 domain_warp(glm::vec2 p, const Fractal& f, float amount) {
    Fractal fx = f, fy = f;
    fx.seed = f.seed ^ 0x51ed270bu;
    fy.seed = f.seed ^ 0x2c1b3c6du;
    const Noise2 qx = fbm(p, fx);
    const Noise2 qy = fbm(p + glm::vec2(5.2f, 1.3f), fy);
    const Noise2 h = fbm(p + amount * glm::vec2(qx.value, qy.value), f);
    return {h.value, h.gradient + amount * (h.gradient.x * qx.gradient + h.gradient.y * qy.gradient)};
}

// Wind-blown sand: transverse dunes whose crests run across the wind, with a gentle windward
// slope and a steep lee face, sinuous crests (the phase is warped by noise), crest heights
// that vary along the crest, and small ripples. Heights in about [0, 1 + ripple_amplitude].
struct Dunes {
    glm::vec2 wind{1.0f, 0.0f};      // unit direction the wind blows towards
    float wavelength = 1.0f;         // crest spacing, in input units
    float lee_fraction = 0.25f;      // share of a wavelength taken by the steep lee face
    float sinuosity = 0.35f;         // crest bending, in wavelengths
    float ripple_wavelength = 0.06f; // wind ripples on top, in input units
    float ripple_amplitude = 0.02f;
    uint32_t seed = 0;
};

namespace dune_detail {
// Asymmetric periodic profile: smootherstep (6x^5 - 15x^4 + 10x^3) up over [0, a), down over
// [a, 1); C2 at the crest and trough (no shading seams), value in [0, 1], and its derivative
// with respect to the phase.
TESSERA_NOISE_INLINE void profile(float phase, float a, float& value, float& slope) {
    const float t = phase - float(floor_int(phase));
    const bool rising = t < a;
    const float span = rising ? a : 1.0f - a;
    const float x = rising ? t / a : (t - a) / (1.0f - a);
    const float s = x * x * x * (x * (x * 6.0f - 15.0f) + 10.0f);
    const float ds = 30.0f * x * x * (1.0f - x) * (1.0f - x) / span;
    value = rising ? s : 1.0f - s;
    slope = rising ? ds : -ds;
}
}  // namespace dune_detail

TESSERA_NOISE_INLINE Noise2 dunes(glm::vec2 p, const Dunes& d) {
    const Fractal bend{3, 2.0f, 0.5f, d.seed};
    const Fractal crest{2, 2.0f, 0.5f, d.seed ^ 0x7f4a7c15u};
    const float inv_wavelength = 1.0f / d.wavelength;
    // Noise is sampled in wavelength units so sinuosity and crest variation scale with it.
    const glm::vec2 q = p * inv_wavelength;
    const Noise2 warp = fbm(q * 0.5f, bend);
    const float phase = (d.wind.x * p.x + d.wind.y * p.y) * inv_wavelength + d.sinuosity * warp.value;
    const glm::vec2 phase_gradient =
        d.wind * inv_wavelength + (d.sinuosity * 0.5f * inv_wavelength) * warp.gradient;
    float shape, shape_slope;
    dune_detail::profile(phase, 1.0f - d.lee_fraction, shape, shape_slope);
    const Noise2 height = fbm(q * 0.7f, crest);
    const float scale = 0.75f + 0.25f * height.value;
    const glm::vec2 scale_gradient = (0.25f * 0.7f * inv_wavelength) * height.gradient;

    // Ripples: the same asymmetric profile at a short wavelength, straight across the wind.
    const float inv_ripple = 1.0f / d.ripple_wavelength;
    float ripple, ripple_slope;
    dune_detail::profile((d.wind.x * p.x + d.wind.y * p.y) * inv_ripple, 0.7f, ripple, ripple_slope);

    return {shape * scale + d.ripple_amplitude * ripple,
            (shape_slope * scale) * phase_gradient + shape * scale_gradient +
                (d.ripple_amplitude * ripple_slope * inv_ripple) * d.wind};
}

}  // namespace tessera::procedural
