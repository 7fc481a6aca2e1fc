// The fractal sums of fractal.h over many points at once (structure of arrays), vectorised over
// the points: what the heightfield generator runs per row and a ray marcher per packet of
// samples. Each form runs the single-point function's octave steps (fractal_detail) in the
// same order on the same lattice, so point i gets exactly what fbm, ridged or domain_warp
// return at (x[i], y[i]) (and z[i]), value and gradient, bit for bit.
//
// With the gradient outputs null (all) only the values are computed: a marcher's steps need no
// gradient, and the noise without its derivative costs about half as much.
#pragma once
#include <cstddef>

#include "procedural/fractal.h"

namespace tessera::procedural {

void fbm_batch(const Fractal& f, OpenLattice lattice, size_t n, const float* x, const float* y,
               float* value, float* dx = nullptr, float* dy = nullptr);
void fbm_batch(const Fractal& f, TorusLattice lattice, size_t n, const float* x, const float* y,
               float* value, float* dx = nullptr, float* dy = nullptr);

void ridged_batch(const Fractal& f, float offset, OpenLattice lattice, size_t n, const float* x,
                  const float* y, float* value, float* dx = nullptr, float* dy = nullptr);
void ridged_batch(const Fractal& f, float offset, TorusLattice lattice, size_t n, const float* x,
                  const float* y, float* value, float* dx = nullptr, float* dy = nullptr);

void domain_warp_batch(const Fractal& f, float amount, OpenLattice lattice, size_t n, const float* x,
                       const float* y, float* value, float* dx = nullptr, float* dy = nullptr);
void domain_warp_batch(const Fractal& f, float amount, TorusLattice lattice, size_t n, const float* x,
                       const float* y, float* value, float* dx = nullptr, float* dy = nullptr);

// 3-D fBm of value noise: fbm(p, f) at each point p = (x[i], y[i], z[i]), bit for bit.
void fbm_batch(const Fractal& f, size_t n, const float* x, const float* y, const float* z, float* value,
               float* dx = nullptr, float* dy = nullptr, float* dz = nullptr);

}  // namespace tessera::procedural
