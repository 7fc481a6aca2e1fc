#include "procedural/dunes.h"

#include "procedural/fractal_batch.h"

#include <algorithm>
#include <cmath>

namespace tessera::procedural {

namespace {
// The wave vector nearest to k with a whole number of waves across the tile on each axis; never
// zero (a wave longer than the tile becomes one wave across it along its main axis).
glm::vec2 snap_wave(glm::vec2 k, glm::ivec2 period) {
    const glm::vec2 waves(std::round(k.x * float(period.x)), std::round(k.y * float(period.y)));
    if (waves == glm::vec2(0.0f)) {
        const bool along_x = std::abs(k.x * float(period.x)) >= std::abs(k.y * float(period.y));
        return along_x ? glm::vec2(std::copysign(1.0f, k.x) / float(period.x), 0.0f)
                       : glm::vec2(0.0f, std::copysign(1.0f, k.y) / float(period.y));
    }
    return waves / glm::vec2(period);
}

// Lattice cells per tile for noise of `frequency` cells per input unit: whole, at least 2.
int tile_cells(float frequency, int period) {
    return int(std::clamp(std::round(double(frequency) * period), 2.0, double(1 << 20)));
}

TorusLattice tile_lattice(float frequency, glm::ivec2 period) {
    return {{tile_cells(frequency, period.x), tile_cells(frequency, period.y)}};
}
}  // namespace

DuneWaves<TorusLattice> dune_waves(const Dunes& d, glm::ivec2 period) {
    const float k = 1.0f / d.wavelength;
    const TorusLattice bend = tile_lattice(0.5f * k, period), height = tile_lattice(0.7f * k, period);
    return {snap_wave(d.wind * k, period), snap_wave(d.wind * (1.0f / d.ripple_wavelength), period),
            glm::vec2(bend.period) / glm::vec2(period), glm::vec2(height.period) / glm::vec2(period),
            bend, height};
}

namespace {

constexpr size_t kBlock = 64;  // points per block of noise scratch

// At most kBlock points: both noises of the block, then the profiles point by point.
template <bool kGradient, class Lattice>
void dunes_block(const Dunes& dunes, const DuneWaves<Lattice>& waves, size_t n, const float* __restrict x,
                 const float* __restrict y, float* __restrict value, float* __restrict dx,
                 float* __restrict dy) {
    const Dunes d = dunes;  // copies: no store to the outputs can change them
    const DuneWaves<Lattice> w = waves;
    float u[kBlock] = {}, v[kBlock] = {};  // (initialised: GCC cannot see the loops below fill them)
    float bend[kBlock], bend_dx[kBlock], bend_dy[kBlock], crest[kBlock], crest_dx[kBlock], crest_dy[kBlock];
    for (size_t i = 0; i < n; ++i) {
        const glm::vec2 q = glm::vec2(x[i], y[i]) * w.bend_scale;
        u[i] = q.x;
        v[i] = q.y;
    }
    fbm_batch(dune_detail::bend_fractal(d), w.bend_lattice, n, u, v, bend, kGradient ? bend_dx : nullptr,
              kGradient ? bend_dy : nullptr);
    for (size_t i = 0; i < n; ++i) {
        const glm::vec2 q = glm::vec2(x[i], y[i]) * w.height_scale;
        u[i] = q.x;
        v[i] = q.y;
    }
    fbm_batch(dune_detail::crest_fractal(d), w.height_lattice, n, u, v, crest, kGradient ? crest_dx : nullptr,
              kGradient ? crest_dy : nullptr);
    for (size_t i = 0; i < n; ++i) {
        Noise2 warp{bend[i], glm::vec2(0.0f)}, height{crest[i], glm::vec2(0.0f)};
        if constexpr (kGradient) {
            warp.gradient = {bend_dx[i], bend_dy[i]};
            height.gradient = {crest_dx[i], crest_dy[i]};
        }
        const Noise2 r = dune_detail::relief(glm::vec2(x[i], y[i]), d, w, warp, height);
        value[i] = r.value;
        if constexpr (kGradient) {
            dx[i] = r.gradient.x;
            dy[i] = r.gradient.y;
        }
    }
}

template <class Lattice>
void dunes_any(const Dunes& d, const DuneWaves<Lattice>& w, size_t n, const float* x, const float* y,
               float* value, float* dx, float* dy) {
    for (size_t start = 0; start < n; start += kBlock) {
        const size_t m = std::min(kBlock, n - start);
        if (dx)
            dunes_block<true>(d, w, m, x + start, y + start, value + start, dx + start, dy + start);
        else
            dunes_block<false>(d, w, m, x + start, y + start, value + start, nullptr, nullptr);
    }
}

}  // namespace

void dunes_batch(const Dunes& d, const DuneWaves<OpenLattice>& w, size_t n, const float* x, const float* y,
                 float* value, float* dx, float* dy) {
    dunes_any(d, w, n, x, y, value, dx, dy);
}

void dunes_batch(const Dunes& d, const DuneWaves<TorusLattice>& w, size_t n, const float* x, const float* y,
                 float* value, float* dx, float* dy) {
    dunes_any(d, w, n, x, y, value, dx, dy);
}

}  // namespace tessera::procedural
