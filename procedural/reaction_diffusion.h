// Gray-Scott reaction-diffusion as Karl Sims discretises it (karlsims.com/rd.html):
//   A' = A + (Da lap(A) - A B^2 + f (1 - A)) dt
//   B' = B + (Db lap(B) + A B^2 - (k + f) B) dt
// with the 3x3 Laplacian (centre -1, edge neighbours 0.2, corners 0.05), Da = 1, Db = 0.5,
// dt = 1. Explicit Euler with double buffering (Jacobi: every cell of step t+1 reads only
// step t), so the result is bit-identical whatever the tiling or thread count.
//
// Parallel over tiles with oneTBB; within a row the interior cells run in a loop GCC
// vectorises (SIMD over x); the edge cells take the boundary rule. A single step goes row by
// row through each row's left + right neighbour sums, computed once and read by the three
// rows that need them (same operations, same bits; see reaction_diffusion.cpp). Runs of steps are
// temporally blocked (4 steps per tile in L2-sized scratch, see reaction_diffusion.cpp), which
// takes large grids past the DRAM bandwidth limit of one pass per step.
#pragma once
#include <cstdint>

#include "procedural/grid.h"

namespace tessera::procedural {

struct GrayScott {
    float feed = 0.055f;  // f: Karl Sims' default image
    float kill = 0.062f;  // k
    float diffusion_a = 1.0f;
    float diffusion_b = 0.5f;
    float dt = 1.0f;
    // In [-1, 1]: moves Laplacian weight from the y neighbours to the x neighbours (edge
    // weights 0.2 (1 + a) along x and 0.2 (1 - a) along y), so the pattern stretches along x
    // for a > 0. 0 is Sims' isotropic kernel.
    float anisotropy = 0.0f;
    Boundary boundary = Boundary::periodic;
    // Optional per-cell feed and kill rates (same size as the grids) replacing feed/kill:
    // patterns that change class across the texture. Not owned; must outlive the simulation.
    const Grid* feed_map = nullptr;
    const Grid* kill_map = nullptr;
};

// The most negative eigenvalue's magnitude of the (possibly anisotropic) Laplacian: 1.6 for
// Sims' kernel (at frequency (pi, pi)), 1.2 + 0.8 |a| when that is larger (at (pi, 0)).
float laplacian_spectral_radius(float anisotropy);

// The largest stable dt: explicit Euler diffusion needs D dt |lambda| <= 2, so with Sims'
// kernel D dt <= 1.25 (Da = 1 at dt = 1 keeps a 25% margin).
float max_stable_dt(const GrayScott& params);

// Throws std::invalid_argument with a one-line reason for NaN or out-of-range values, an
// unstable dt (naming the limit), or feed/kill maps whose size differs from width x height.
void validate(const GrayScott& params, int width, int height);

// The two concentrations, each a grid of the same size, values in [0, 1].
struct RdState {
    Grid a;
    Grid b;
};

class ReactionDiffusion {
public:
    // Validates params against the state's size; the state is the initial condition.
    ReactionDiffusion(const GrayScott& params, RdState initial);

    // Advances `steps` time steps. The result is the same, bit for bit, however the steps are
    // split across calls and whatever the thread count.
    void step(int steps = 1);

    const RdState& state() const { return current_; }
    const GrayScott& params() const { return params_; }
    int64_t steps_done() const { return steps_done_; }

private:
    GrayScott params_;
    RdState current_;
    RdState next_;
    int64_t steps_done_ = 0;
};

}  // namespace tessera::procedural
