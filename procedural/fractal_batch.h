// fBm over many points at once (structure of arrays), vectorised over the points: what the
// heightfield generator runs per row and a ray marcher per packet of samples. Each point gets
// fbm(p * scale) and its gradient with respect to p (that is, scale * the gradient fbm() of
// fractal.h returns at p * scale), equal to the single-point form up to rounding.
#pragma once
#include <cstddef>

#include "procedural/fractal.h"

namespace tessera::procedural {

void fbm_batch(const Fractal& f, float scale, size_t n, const float* x, const float* y,
               float* value, float* dx, float* dy);

// Tileable form: see fbm_periodic (period in octave-0 lattice cells, after scaling).
void fbm_periodic_batch(const Fractal& f, glm::ivec2 period, float scale, size_t n,
                        const float* x, const float* y, float* value, float* dx, float* dy);

void fbm_batch(const Fractal& f, float scale, size_t n, const float* x, const float* y,
               const float* z, float* value, float* dx, float* dy, float* dz);

}  // namespace tessera::procedural
