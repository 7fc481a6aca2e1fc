// Batch fractal sums: the octave loop outside, the point loop inside, so the point loop is a
// straight line of lane-wise noise that GCC vectorises (a per-point octave loop inside a point
// loop is a loop nest it will not vectorise). Per-point running sums live in the output arrays
// or in block-sized scratch; each octave of each point is the single-point step of fractal.h.
#include "procedural/fractal_batch.h"

#include <algorithm>

namespace tessera::procedural {

namespace {

// Points per block of the sums that need scratch beside their outputs (the ridged weights, the
// warp fields): small enough for the stack and L1, large enough to amortise each octave's key.
constexpr size_t kBlock = 64;

// Divides the sums (and their gradients; dz only for 3-D sums) by the fractal's total
// amplitude, as fractal.h's single-point sums do after their octave loop.
template <bool kGradient>
void normalise(const Fractal& f, size_t n, float* __restrict value, float* __restrict dx, float* __restrict dy,
               float* __restrict dz = nullptr) {
    const float norm = 1.0f / fractal_amplitude(f);
    for (size_t i = 0; i < n; ++i) value[i] = value[i] * norm;
    if constexpr (kGradient) {
        for (size_t i = 0; i < n; ++i) {
            dx[i] = dx[i] * norm;
            dy[i] = dy[i] * norm;
        }
        if (dz)
            for (size_t i = 0; i < n; ++i) dz[i] = dz[i] * norm;
    }
}

template <bool kGradient, class Lattice>
void fbm2(const Fractal& f, Lattice lattice, size_t n, const float* __restrict x, const float* __restrict y,
          float* __restrict value, float* __restrict dx, float* __restrict dy) {
    for (size_t i = 0; i < n; ++i) value[i] = 0.0f;
    if constexpr (kGradient)
        for (size_t i = 0; i < n; ++i) dx[i] = dy[i] = 0.0f;
    float amplitude = 1.0f, frequency = 1.0f;
    for (int octave = 0; octave < f.octaves; ++octave) {
        const uint32_t key = noise_detail::seed_key(octave_seed(f.seed, octave));
        for (size_t i = 0; i < n; ++i) {
            Noise2 sum{value[i], glm::vec2(0.0f)};
            if constexpr (kGradient) sum.gradient = {dx[i], dy[i]};
            fractal_detail::fbm_octave(sum, lattice.value_at(key, glm::vec2(x[i], y[i]) * frequency), amplitude,
                                       frequency);
            value[i] = sum.value;
            if constexpr (kGradient) {
                dx[i] = sum.gradient.x;
                dy[i] = sum.gradient.y;
            }
        }
        amplitude *= f.gain;
        frequency *= f.lacunarity;
        lattice = lattice.finer(int(f.lacunarity));
    }
    normalise<kGradient>(f, n, value, dx, dy);
}

// At most kBlock points.
template <bool kGradient, class Lattice>
void ridged2_block(const Fractal& f, float offset, Lattice lattice, size_t n, const float* __restrict x,
                   const float* __restrict y, float* __restrict value, float* __restrict dx,
                   float* __restrict dy) {
    float weight[kBlock], wx[kBlock], wy[kBlock];
    for (size_t i = 0; i < n; ++i) {
        value[i] = 0.0f;
        weight[i] = 1.0f;
    }
    if constexpr (kGradient)
        for (size_t i = 0; i < n; ++i) dx[i] = dy[i] = wx[i] = wy[i] = 0.0f;
    float amplitude = 1.0f, frequency = 1.0f;
    for (int octave = 0; octave < f.octaves; ++octave) {
        const uint32_t key = noise_detail::seed_key(octave_seed(f.seed, octave));
        for (size_t i = 0; i < n; ++i) {
            fractal_detail::RidgedSum sum;
            sum.value = value[i];
            sum.weight = weight[i];
            if constexpr (kGradient) {
                sum.gradient = {dx[i], dy[i]};
                sum.weight_gradient = {wx[i], wy[i]};
            }
            fractal_detail::ridged_octave(sum, lattice.gradient_at(key, glm::vec2(x[i], y[i]) * frequency),
                                          amplitude, frequency, offset);
            value[i] = sum.value;
            weight[i] = sum.weight;
            if constexpr (kGradient) {
                dx[i] = sum.gradient.x;
                dy[i] = sum.gradient.y;
                wx[i] = sum.weight_gradient.x;
                wy[i] = sum.weight_gradient.y;
            }
        }
        amplitude *= f.gain;
        frequency *= f.lacunarity;
        lattice = lattice.finer(int(f.lacunarity));
    }
    normalise<kGradient>(f, n, value, dx, dy);
}

// At most kBlock points: the two warp fields, the warped points, then the warped fBm.
template <bool kGradient, class Lattice>
void warp2_block(const Fractal& f, float amount, Lattice lattice, size_t n, const float* __restrict x,
                 const float* __restrict y, float* __restrict value, float* __restrict dx,
                 float* __restrict dy) {
    using namespace fractal_detail;
    float qx[kBlock], qx_dx[kBlock], qx_dy[kBlock], qy[kBlock], qy_dx[kBlock], qy_dy[kBlock];
    float u[kBlock] = {}, v[kBlock] = {};  // (initialised: GCC cannot see the loops below fill them)
    fbm2<kGradient>(warp_x(f), lattice, n, x, y, qx, qx_dx, qx_dy);
    for (size_t i = 0; i < n; ++i) {
        const glm::vec2 p = glm::vec2(x[i], y[i]) + kWarpYOffset;
        u[i] = p.x;
        v[i] = p.y;
    }
    fbm2<kGradient>(warp_y(f), lattice, n, u, v, qy, qy_dx, qy_dy);
    for (size_t i = 0; i < n; ++i) {
        const glm::vec2 p = glm::vec2(x[i], y[i]) + amount * glm::vec2(qx[i], qy[i]);
        u[i] = p.x;
        v[i] = p.y;
    }
    fbm2<kGradient>(f, lattice, n, u, v, value, dx, dy);
    if constexpr (kGradient)
        for (size_t i = 0; i < n; ++i) {
            const Noise2 r = warp_chain({value[i], {dx[i], dy[i]}}, {qx[i], {qx_dx[i], qx_dy[i]}},
                                        {qy[i], {qy_dx[i], qy_dy[i]}}, amount);
            dx[i] = r.gradient.x;
            dy[i] = r.gradient.y;
        }
}

// Runs `block` over kBlock-point pieces, with or without gradients.
template <class Block>
void in_blocks(size_t n, const float* x, const float* y, float* value, float* dx, float* dy, Block block) {
    for (size_t start = 0; start < n; start += kBlock) {
        const size_t count = std::min(kBlock, n - start);
        if (dx)
            block(std::true_type{}, count, x + start, y + start, value + start, dx + start, dy + start);
        else
            block(std::false_type{}, count, x + start, y + start, value + start, nullptr, nullptr);
    }
}

template <class Lattice>
void ridged2(const Fractal& f, float offset, Lattice lattice, size_t n, const float* x, const float* y,
             float* value, float* dx, float* dy) {
    in_blocks(n, x, y, value, dx, dy, [&](auto gradient, size_t m, const float* bx, const float* by, float* bv,
                                          float* bdx, float* bdy) {
        ridged2_block<decltype(gradient)::value>(f, offset, lattice, m, bx, by, bv, bdx, bdy);
    });
}

template <class Lattice>
void warp2(const Fractal& f, float amount, Lattice lattice, size_t n, const float* x, const float* y,
           float* value, float* dx, float* dy) {
    in_blocks(n, x, y, value, dx, dy, [&](auto gradient, size_t m, const float* bx, const float* by, float* bv,
                                          float* bdx, float* bdy) {
        warp2_block<decltype(gradient)::value>(f, amount, lattice, m, bx, by, bv, bdx, bdy);
    });
}

template <class Lattice>
void fbm2_any(const Fractal& f, Lattice lattice, size_t n, const float* x, const float* y, float* value,
              float* dx, float* dy) {
    if (dx)
        fbm2<true>(f, lattice, n, x, y, value, dx, dy);
    else
        fbm2<false>(f, lattice, n, x, y, value, nullptr, nullptr);
}

}  // namespace

void fbm_batch(const Fractal& f, OpenLattice lattice, size_t n, const float* x, const float* y, float* value,
               float* dx, float* dy) {
    fbm2_any(f, lattice, n, x, y, value, dx, dy);
}

void fbm_batch(const Fractal& f, TorusLattice lattice, size_t n, const float* x, const float* y, float* value,
               float* dx, float* dy) {
    fbm2_any(f, lattice, n, x, y, value, dx, dy);
}

void ridged_batch(const Fractal& f, float offset, OpenLattice lattice, size_t n, const float* x, const float* y,
                  float* value, float* dx, float* dy) {
    ridged2(f, offset, lattice, n, x, y, value, dx, dy);
}

void ridged_batch(const Fractal& f, float offset, TorusLattice lattice, size_t n, const float* x, const float* y,
                  float* value, float* dx, float* dy) {
    ridged2(f, offset, lattice, n, x, y, value, dx, dy);
}

void domain_warp_batch(const Fractal& f, float amount, OpenLattice lattice, size_t n, const float* x,
                       const float* y, float* value, float* dx, float* dy) {
    warp2(f, amount, lattice, n, x, y, value, dx, dy);
}

void domain_warp_batch(const Fractal& f, float amount, TorusLattice lattice, size_t n, const float* x,
                       const float* y, float* value, float* dx, float* dy) {
    warp2(f, amount, lattice, n, x, y, value, dx, dy);
}

namespace {

template <bool kGradient>
void fbm3(const Fractal& f, size_t n, const float* __restrict x, const float* __restrict y,
          const float* __restrict z, float* __restrict value, float* __restrict dx, float* __restrict dy,
          float* __restrict dz) {
    for (size_t i = 0; i < n; ++i) value[i] = 0.0f;
    if constexpr (kGradient)
        for (size_t i = 0; i < n; ++i) dx[i] = dy[i] = dz[i] = 0.0f;
    float amplitude = 1.0f, frequency = 1.0f;
    for (int octave = 0; octave < f.octaves; ++octave) {
        const uint32_t seed = octave_seed(f.seed, octave);
        for (size_t i = 0; i < n; ++i) {
            Noise3 sum{value[i], glm::vec3(0.0f)};
            if constexpr (kGradient) sum.gradient = {dx[i], dy[i], dz[i]};
            fractal_detail::fbm_octave(sum, value_noise(glm::vec3(x[i], y[i], z[i]) * frequency, seed), amplitude,
                                       frequency);
            value[i] = sum.value;
            if constexpr (kGradient) {
                dx[i] = sum.gradient.x;
                dy[i] = sum.gradient.y;
                dz[i] = sum.gradient.z;
            }
        }
        amplitude *= f.gain;
        frequency *= f.lacunarity;
    }
    normalise<kGradient>(f, n, value, dx, dy, dz);
}

}  // namespace

void fbm_batch(const Fractal& f, size_t n, const float* x, const float* y, const float* z, float* value,
               float* dx, float* dy, float* dz) {
    if (dx)
        fbm3<true>(f, n, x, y, z, value, dx, dy, dz);
    else
        fbm3<false>(f, n, x, y, z, value, nullptr, nullptr, nullptr);
}

}  // namespace tessera::procedural
