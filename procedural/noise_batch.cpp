// Batch noise: the inline single-point functions of noise.h in loops the compiler vectorises
// (every lattice hash, floor and blend is lane-wise, with no branches), so one call shades a
// whole packet of ray samples or a row of a heightfield.
#include "procedural/noise.h"

// The per-point lambdas must inline into the loop for it to vectorise.
#if defined(__GNUC__)
#define TESSERA_NOISE_LAMBDA __attribute__((always_inline))
#else
#define TESSERA_NOISE_LAMBDA
#endif

namespace tessera::procedural {

namespace {
template <bool kGradient, class Noise>
void batch(Noise noise, size_t n, const float* __restrict x, const float* __restrict y,
           const float* __restrict z, float* __restrict value, float* __restrict dx,
           float* __restrict dy, float* __restrict dz) {
    for (size_t i = 0; i < n; ++i) {
        const Noise3 s = noise(glm::vec3(x[i], y[i], z[i]));
        value[i] = s.value;
        if constexpr (kGradient) {  // otherwise the derivative arithmetic is dead code
            dx[i] = s.gradient.x;
            dy[i] = s.gradient.y;
            dz[i] = s.gradient.z;
        }
    }
}

template <class Noise>
void batch_any(Noise noise, size_t n, const float* x, const float* y, const float* z, float* value, float* dx,
               float* dy, float* dz) {
    if (dx)
        batch<true>(noise, n, x, y, z, value, dx, dy, dz);
    else
        batch<false>(noise, n, x, y, z, value, nullptr, nullptr, nullptr);
}
}  // namespace

void value_noise_batch(uint32_t seed, size_t n, const float* x, const float* y, const float* z,
                       float* value, float* dx, float* dy, float* dz) {
    batch_any([seed](glm::vec3 p) TESSERA_NOISE_LAMBDA { return value_noise(p, seed); }, n, x, y, z, value, dx, dy, dz);
}

void gradient_noise_batch(uint32_t seed, size_t n, const float* x, const float* y,
                          const float* z, float* value, float* dx, float* dy, float* dz) {
    batch_any([seed](glm::vec3 p) TESSERA_NOISE_LAMBDA { return gradient_noise(p, seed); }, n, x, y, z, value, dx, dy, dz);
}

}  // namespace tessera::procedural
