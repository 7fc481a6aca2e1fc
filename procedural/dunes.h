// Wind-blown sand: transverse dunes whose crests run across the wind, with a gentle windward
// slope and a steep lee face, sinuous crests (the phase is warped by noise), crest heights
// that vary along the crest, and small ripples. Heights in about [0, 1 + ripple_amplitude].
//
// The relief is evaluated from DuneWaves: its wave vectors and noise lattices. dune_waves(d)
// gives the open plane; dune_waves(d, period) gives a relief that repeats every period input
// units on each axis, for tileable textures (the heightfield's octave-0 cells).
#pragma once
#include <glm/vec2.hpp>

#include <cstddef>
#include <cstdint>

#include "procedural/fractal.h"

namespace tessera::procedural {

struct Dunes {
    glm::vec2 wind{1.0f, 0.0f};      // unit direction the wind blows towards
    float wavelength = 1.0f;         // crest spacing, in input units
    float lee_fraction = 0.25f;      // share of a wavelength taken by the steep lee face
    float sinuosity = 0.35f;         // crest bending, in wavelengths
    float ripple_wavelength = 0.06f; // wind ripples on top, in input units
    float ripple_amplitude = 0.02f;
    uint32_t seed = 0;
};

// The waves of a dune field. A profile's phase is dot(wave vector, p) (one cycle per crest or
// ripple); the bending and crest-height noise are fBm at p * scale on their lattices.
template <class Lattice>
struct DuneWaves {
    glm::vec2 crest;         // crests: wind / wavelength
    glm::vec2 ripple;        // ripples: wind / ripple_wavelength
    glm::vec2 bend_scale;    // crest bending noise: 0.5 lattice cells per wavelength
    glm::vec2 height_scale;  // crest height noise: 0.7 lattice cells per wavelength
    Lattice bend_lattice, height_lattice;
};

inline DuneWaves<OpenLattice> dune_waves(const Dunes& d) {
    const float k = 1.0f / d.wavelength;
    return {d.wind * k, d.wind * (1.0f / d.ripple_wavelength), glm::vec2(0.5f * k),
            glm::vec2(0.7f * k), {}, {}};
}

// Waves that repeat every period.x by period.y input units (> 0): each wave vector is snapped
// to the nearest one with a whole number of waves across the tile on each axis (so crests meet
// themselves at the edges; a wave longer than the tile becomes one wave across it), and each
// noise scale to a whole number of lattice cells per tile, at least 2 (a repeating lattice of
// one cell is constant along that axis).
DuneWaves<TorusLattice> dune_waves(const Dunes& d, glm::ivec2 period);

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

// The two noises of a dune field: the crest bending and the crest height.
inline Fractal bend_fractal(const Dunes& d) { return {3, 2.0f, 0.5f, d.seed}; }
inline Fractal crest_fractal(const Dunes& d) { return {2, 2.0f, 0.5f, d.seed ^ 0x7f4a7c15u}; }

// The relief at p from its two noises, `warp` = fbm(p * bend_scale) and `height` =
// fbm(p * height_scale): what dunes() and the batch loop of dunes_batch both run.
template <class Lattice>
TESSERA_NOISE_INLINE Noise2 relief(glm::vec2 p, const Dunes& d, const DuneWaves<Lattice>& w, Noise2 warp,
                                   Noise2 height) {
    const float phase = w.crest.x * p.x + w.crest.y * p.y + d.sinuosity * warp.value;
    const glm::vec2 phase_gradient = w.crest + d.sinuosity * (w.bend_scale * warp.gradient);
    float shape, shape_slope;
    profile(phase, 1.0f - d.lee_fraction, shape, shape_slope);
    const float scale = 0.75f + 0.25f * height.value;
    const glm::vec2 scale_gradient = 0.25f * (w.height_scale * height.gradient);

    // Ripples: the same asymmetric profile at a short wavelength, straight across the wind.
    float ripple, ripple_slope;
    profile(w.ripple.x * p.x + w.ripple.y * p.y, 0.7f, ripple, ripple_slope);

    return {shape * scale + d.ripple_amplitude * ripple,
            (shape_slope * scale) * phase_gradient + shape * scale_gradient +
                (d.ripple_amplitude * ripple_slope) * w.ripple};
}
}  // namespace dune_detail

// The relief and its gradient: the chain rule through each wave's phase and each noise's scale.
// Noise scales with the wavelength, so sinuosity and crest variation do too.
template <class Lattice>
TESSERA_NOISE_INLINE Noise2 dunes(glm::vec2 p, const Dunes& d, const DuneWaves<Lattice>& w) {
    return dune_detail::relief(p, d, w, fbm(p * w.bend_scale, dune_detail::bend_fractal(d), w.bend_lattice),
                               fbm(p * w.height_scale, dune_detail::crest_fractal(d), w.height_lattice));
}

TESSERA_NOISE_INLINE Noise2 dunes(glm::vec2 p, const Dunes& d) { return dunes(p, d, dune_waves(d)); }

// dunes() over n points (x[i], y[i]), vectorised over the points (the two noises through
// fbm_batch, then the profiles): point i gets the single call's value and gradient bit for
// bit. With dx and dy null (both) only the values are computed.
void dunes_batch(const Dunes& d, const DuneWaves<OpenLattice>& w, size_t n, const float* x, const float* y,
                 float* value, float* dx = nullptr, float* dy = nullptr);
void dunes_batch(const Dunes& d, const DuneWaves<TorusLattice>& w, size_t n, const float* x, const float* y,
                 float* value, float* dx = nullptr, float* dy = nullptr);

}  // namespace tessera::procedural
