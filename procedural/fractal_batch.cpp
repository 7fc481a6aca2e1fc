// Batch fBm: the octave loop outside, the point loop inside, so the point loop is a straight
// line of lane-wise noise that GCC vectorises (a per-point octave loop inside a point loop is a
// loop nest it will not vectorise). The sums run in the same octave order as fbm() in
// fractal.h, so a batch agrees with the single-point calls.
#include "procedural/fractal_batch.h"

namespace tessera::procedural {

namespace {

// The octave sum of both 2-D forms. The lattice gives an octave's noise at a point already
// scaled by the octave's frequency (`at`) and how the frequency grows (`lacunarity`);
// `next_octave` lets a periodic lattice multiply its period with the frequency.
template <class Lattice>
void fbm2_batch(const Fractal& f, Lattice lattice, float scale, size_t n, const float* __restrict x,
                const float* __restrict y, float* __restrict value, float* __restrict dx, float* __restrict dy) {
    for (size_t i = 0; i < n; ++i) value[i] = dx[i] = dy[i] = 0.0f;
    float amplitude = 1.0f, frequency = scale;
    for (int octave = 0; octave < f.octaves; ++octave) {
        const uint32_t key = noise_detail::seed_key(octave_seed(f.seed, octave));
        const float slope = amplitude * frequency;
        for (size_t i = 0; i < n; ++i) {
            const Noise2 s = lattice.at(key, x[i] * frequency, y[i] * frequency);
            value[i] += amplitude * s.value;
            dx[i] += slope * s.gradient.x;
            dy[i] += slope * s.gradient.y;
        }
        amplitude *= f.gain;
        frequency *= lattice.lacunarity;
        lattice.next_octave();
    }
    const float norm = 1.0f / fractal_amplitude(f);
    for (size_t i = 0; i < n; ++i) {
        value[i] *= norm;
        dx[i] *= norm;
        dy[i] *= norm;
    }
}

struct PlainLattice {
    float lacunarity;
    TESSERA_NOISE_INLINE Noise2 at(uint32_t key, float x, float y) const {
        using namespace noise_detail;
        return value2(key, axis(x, kPrimeX), axis(y, kPrimeY));
    }
    void next_octave() {}
};

// fbm_periodic's lattice: a whole lacunarity, so each octave's period is a whole number of cells.
struct PeriodicLattice {
    glm::ivec2 period;
    int factor;
    float lacunarity = float(factor);
    TESSERA_NOISE_INLINE Noise2 at(uint32_t key, float x, float y) const {
        using namespace noise_detail;
        return value2(key, periodic_axis(x, period.x, kPrimeX), periodic_axis(y, period.y, kPrimeY));
    }
    void next_octave() { period *= factor; }
};

}  // namespace

void fbm_batch(const Fractal& f, float scale, size_t n, const float* __restrict x,
               const float* __restrict y, float* __restrict value, float* __restrict dx,
               float* __restrict dy) {
    fbm2_batch(f, PlainLattice{f.lacunarity}, scale, n, x, y, value, dx, dy);
}

void fbm_periodic_batch(const Fractal& f, glm::ivec2 period, float scale, size_t n,
                        const float* __restrict x, const float* __restrict y,
                        float* __restrict value, float* __restrict dx, float* __restrict dy) {
    fbm2_batch(f, PeriodicLattice{period, int(f.lacunarity)}, scale, n, x, y, value, dx, dy);
}

void fbm_batch(const Fractal& f, float scale, size_t n, const float* __restrict x,
               const float* __restrict y, const float* __restrict z, float* __restrict value,
               float* __restrict dx, float* __restrict dy, float* __restrict dz) {
    for (size_t i = 0; i < n; ++i) value[i] = dx[i] = dy[i] = dz[i] = 0.0f;
    float amplitude = 1.0f, frequency = scale;
    for (int octave = 0; octave < f.octaves; ++octave) {
        const uint32_t seed = octave_seed(f.seed, octave);
        const float slope = amplitude * frequency;
        for (size_t i = 0; i < n; ++i) {
            const Noise3 s = value_noise(glm::vec3(x[i], y[i], z[i]) * frequency, seed);
            value[i] += amplitude * s.value;
            dx[i] += slope * s.gradient.x;
            dy[i] += slope * s.gradient.y;
            dz[i] += slope * s.gradient.z;
        }
        amplitude *= f.gain;
        frequency *= f.lacunarity;
    }
    const float norm = 1.0f / fractal_amplitude(f);
    for (size_t i = 0; i < n; ++i) {
        value[i] *= norm;
        dx[i] *= norm;
        dy[i] *= norm;
        dz[i] *= norm;
    }
}

}  // namespace tessera::procedural
