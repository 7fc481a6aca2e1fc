// The fractal sums of fractal.h over many points at once (structure of arrays), vectorised over
// the points: what the heightfield generator runs per row and a ray marcher per packet of
// samples. Each 2-D form runs the single-point function's octave steps (fractal_detail) in
// the same order on the same lattice, so point i gets exactly what fbm, ridged or domain_warp
// return at (x[i], y[i]), value and gradient, bit for bit.
//
// With dx and dy null (both) only the values are computed: a marcher's steps need no
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

// 3-D fBm of value noise: each point gets fbm(p * scale) and its gradient with respect to p
// (that is, scale * the gradient fbm() of fractal.h returns at p * scale), equal to the
// single-point form up to rounding.
void fbm_batch(const Fractal& f, float scale, size_t n, const float* x, const float* y,
               const float* z, float* value, float* dx, float* dy, float* dz);

}  // namespace tessera::procedural
