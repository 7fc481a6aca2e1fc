// Batch forms of the implicit fields: the inline per-point code of field.h in loops over
// structure-of-arrays samples, which GCC vectorises (checked with -fopt-info-vec); the base
// class's plain loops serve fields that have no faster form.
#include "procedural/field.h"

#include "procedural/fractal_batch.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace tessera::procedural {

void ImplicitField::value_batch(size_t n, const float* x, const float* y, const float* z,
                                float* value) const {
    for (size_t i = 0; i < n; ++i) value[i] = this->value(glm::vec3(x[i], y[i], z[i]));
}

void ImplicitField::sample_batch(size_t n, const float* x, const float* y, const float* z,
                                 float* value, float* gx, float* gy, float* gz) const {
    for (size_t i = 0; i < n; ++i) {
        const FieldSample s = sample(glm::vec3(x[i], y[i], z[i]));
        value[i] = s.value;
        gx[i] = s.gradient.x;
        gy[i] = s.gradient.y;
        gz[i] = s.gradient.z;
    }
}

// --- SineNoiseField -------------------------------------------------------------------------

SineNoiseField::SineNoiseField() {
    // s = mod(s, 32768) * 2 + floor(s / 32768): a left rotation of each 16-bit component.
    uint32_t s[3] = {7502, 22777, 4767};
    for (glm::vec3& k : waves_) {
        k = glm::vec3(float(int(s[0]) - 32768), float(int(s[1]) - 32768), float(int(s[2]) - 32768)) *
            (40.0f / 65536.0f);
        for (uint32_t& c : s) c = (c % 32768u) * 2u + c / 32768u;
    }
}

// Waves outside, samples inside: the sample loop is a straight line of lane-wise sincos that
// vectorises (a 16-wave loop inside the sample loop would not), and each sample still sums its
// waves in order 0..15, as value() and sample() do.
void SineNoiseField::value_batch(size_t n, const float* __restrict x, const float* __restrict y,
                                 const float* __restrict z, float* __restrict value) const {
    for (size_t i = 0; i < n; ++i) value[i] = 0.0f;
    for (const glm::vec3& k : waves_)
        for (size_t i = 0; i < n; ++i) {
            float s, c;
            sincos_approx(k.x * x[i] + k.y * y[i] + k.z * z[i], s, c);
            value[i] += s;
        }
    for (size_t i = 0; i < n; ++i) value[i] = value[i] * (1.0f / 32.0f) + 0.5f - y[i];
}

void SineNoiseField::sample_batch(size_t n, const float* __restrict x, const float* __restrict y,
                                  const float* __restrict z, float* __restrict value,
                                  float* __restrict gx, float* __restrict gy,
                                  float* __restrict gz) const {
    for (size_t i = 0; i < n; ++i) value[i] = gx[i] = gy[i] = gz[i] = 0.0f;
    for (const glm::vec3& k : waves_) {
        const float kx = k.x, ky = k.y, kz = k.z;
        for (size_t i = 0; i < n; ++i) {
            float s, c;
            sincos_approx(kx * x[i] + ky * y[i] + kz * z[i], s, c);
            value[i] += s;
            gx[i] += c * kx;
            gy[i] += c * ky;
            gz[i] += c * kz;
        }
    }
    for (size_t i = 0; i < n; ++i) {
        value[i] = value[i] * (1.0f / 32.0f) + 0.5f - y[i];
        gx[i] *= 1.0f / 32.0f;
        gy[i] = gy[i] * (1.0f / 32.0f) - 1.0f;
        gz[i] *= 1.0f / 32.0f;
    }
}

// --- TerrainField ---------------------------------------------------------------------------

namespace {
void check_fractal(const Fractal& f, const char* what) {
    if (f.octaves < 1 || f.octaves > 24)
        throw std::invalid_argument(std::string(what) + ": octaves must be in 1..24");
    if (!(f.lacunarity >= 1.0f && f.lacunarity <= 16.0f) || !(f.gain > 0.0f && f.gain < 1.0f))
        throw std::invalid_argument(std::string(what) +
                                    ": lacunarity must be in [1, 16] and gain in (0, 1)");
}
}  // namespace

TerrainField::TerrainField(const TerrainParams& params) : p_(params) {
    check_fractal(p_.fractal, "terrain");
    if (!(p_.frequency > 0.0f) || !std::isfinite(p_.amplitude) || !std::isfinite(p_.base) ||
        !std::isfinite(p_.warp) || !(p_.dunes.wavelength > 0.0f))
        throw std::invalid_argument("terrain: frequency and wavelength must be positive and "
                                    "amplitude, base and warp finite");
    // Noise lattice coordinates are x * frequency, floored to integers: beyond 1e6 cycles per
    // unit they leave the range where that is exact within any sensible view (and 3e38 turns
    // them to Inf: a black terrain). Heights beyond 1e18 overflow when squared.
    if (p_.frequency > 1e6f || std::fabs(p_.amplitude) > 1e18f || std::fabs(p_.base) > 1e18f)
        throw std::invalid_argument("terrain: frequency must be at most 1e6 and amplitude and base within +-1e18");
}

void TerrainField::relief_batch(size_t n, const float* qx, const float* qz, float* r, float* dqx,
                                float* dqz) const {
    switch (p_.relief) {
        case Relief::fbm: fbm_batch(p_.fractal, OpenLattice{}, n, qx, qz, r, dqx, dqz); break;
        case Relief::ridged: ridged_batch(p_.fractal, 1.0f, OpenLattice{}, n, qx, qz, r, dqx, dqz); break;
        case Relief::warped: domain_warp_batch(p_.fractal, p_.warp, OpenLattice{}, n, qx, qz, r, dqx, dqz); break;
        case Relief::dunes: dunes_batch(p_.dunes, dune_waves(p_.dunes), n, qx, qz, r, dqx, dqz); break;
    }
}

// height() over blocks of points: the lattice coordinates, the relief in one batch, then each
// point finished as height() finishes it, so every value and gradient is height()'s.
template <bool kGradient>
void TerrainField::heights(size_t n, const float* x, const float* y, const float* z, float* value,
                           float* gx, float* gz) const {
    constexpr size_t kBlock = 64;
    float qx[kBlock] = {}, qz[kBlock] = {};  // (initialised: GCC cannot see the loop below fill them)
    float r[kBlock], rx[kBlock], rz[kBlock];
    for (size_t start = 0; start < n; start += kBlock) {
        const size_t m = std::min(kBlock, n - start);
        for (size_t i = 0; i < m; ++i) {
            const glm::vec2 q = glm::vec2(x[start + i], z[start + i]) * p_.frequency;
            qx[i] = q.x;
            qz[i] = q.y;
        }
        relief_batch(m, qx, qz, r, kGradient ? rx : nullptr, kGradient ? rz : nullptr);
        for (size_t i = 0; i < m; ++i) {
            Noise2 relief{r[i], glm::vec2(0.0f)};
            if constexpr (kGradient) relief.gradient = {rx[i], rz[i]};
            const Noise2 h = height_of_relief(relief);
            value[start + i] = h.value - y[start + i];
            if constexpr (kGradient) {
                gx[start + i] = h.gradient.x;
                gz[start + i] = h.gradient.y;
            }
        }
    }
}

void TerrainField::value_batch(size_t n, const float* x, const float* y, const float* z,
                               float* value) const {
    heights<false>(n, x, y, z, value, nullptr, nullptr);
}

void TerrainField::sample_batch(size_t n, const float* x, const float* y, const float* z, float* value,
                                float* gx, float* gy, float* gz) const {
    heights<true>(n, x, y, z, value, gx, gz);
    for (size_t i = 0; i < n; ++i) gy[i] = -1.0f;
}

// --- NoiseVolumeField -----------------------------------------------------------------------

NoiseVolumeField::NoiseVolumeField(const VolumeParams& params) : p_(params) {
    check_fractal(p_.fractal, "noise volume");
    if (!(p_.frequency > 0.0f) || !std::isfinite(p_.amplitude) || !std::isfinite(p_.base))
        throw std::invalid_argument("noise volume: frequency must be positive and amplitude and "
                                    "base finite");
}

// sample() over blocks of points: the lattice coordinates, fbm_batch, then each point finished
// as sample() finishes it, so every value and gradient is sample()'s.
template <bool kGradient>
void NoiseVolumeField::samples(size_t n, const float* x, const float* y, const float* z, float* value,
                               float* gx, float* gy, float* gz) const {
    constexpr size_t kBlock = 64;
    float qx[kBlock] = {}, qy[kBlock] = {}, qz[kBlock] = {};  // (initialised: GCC cannot see the loop below fill them)
    float r[kBlock], rx[kBlock], ry[kBlock], rz[kBlock];
    for (size_t start = 0; start < n; start += kBlock) {
        const size_t m = std::min(kBlock, n - start);
        for (size_t i = 0; i < m; ++i) {
            const glm::vec3 q = glm::vec3(x[start + i], y[start + i], z[start + i]) * p_.frequency;
            qx[i] = q.x;
            qy[i] = q.y;
            qz[i] = q.z;
        }
        fbm_batch(p_.fractal, m, qx, qy, qz, r, kGradient ? rx : nullptr, kGradient ? ry : nullptr,
                  kGradient ? rz : nullptr);
        for (size_t i = 0; i < m; ++i) {
            Noise3 noise{r[i], glm::vec3(0.0f)};
            if constexpr (kGradient) noise.gradient = {rx[i], ry[i], rz[i]};
            const FieldSample s =
                sample_of(glm::vec3(x[start + i], y[start + i], z[start + i]), noise);
            value[start + i] = s.value;
            if constexpr (kGradient) {
                gx[start + i] = s.gradient.x;
                gy[start + i] = s.gradient.y;
                gz[start + i] = s.gradient.z;
            }
        }
    }
}

void NoiseVolumeField::value_batch(size_t n, const float* x, const float* y, const float* z,
                                   float* value) const {
    samples<false>(n, x, y, z, value, nullptr, nullptr, nullptr);
}

void NoiseVolumeField::sample_batch(size_t n, const float* x, const float* y, const float* z, float* value,
                                    float* gx, float* gy, float* gz) const {
    samples<true>(n, x, y, z, value, gx, gy, gz);
}

}  // namespace tessera::procedural
