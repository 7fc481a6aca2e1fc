// Thermal erosion of a heightfield (Olsen 2004, "Realtime Procedural Terrain Generation"):
// where a cell is higher than a von Neumann neighbour by more than the talus threshold T,
// material slides down: the cell loses c (d_max - T), shared among its lower neighbours in
// proportion to their drops d_i (only drops > T count). Von Neumann neighbours are Olsen's
// recommendation (as convincing as Moore, half the work).
//
// Olsen updates cells in place, which makes the result depend on the visiting order. Here every
// iteration is a Jacobi step in two passes over the rows (oneTBB): first each cell's outflow
// factor from the old heights, then each cell's new height = old - outflow + what its higher
// neighbours send it. Material is conserved, and the result is bit-identical for any thread
// count.
#pragma once
#include "procedural/grid.h"

namespace tessera::procedural {

struct ThermalErosion {
    int iterations = 50;
    float talus = 0.0f;     // T in height units per cell; <= 0 picks Olsen's 4 / N (N = width)
    float rate = 0.5f;      // c in (0, 0.5]: the share of the excess drop moved per iteration
    Boundary boundary = Boundary::periodic;  // clamped: no material crosses the edges
};

// Erodes `heights` in place. Throws std::invalid_argument for a rate outside (0, 0.5] (more
// can overshoot and oscillate), a NaN talus or negative iterations.
void erode_thermal(Grid& heights, const ThermalErosion& params);

}  // namespace tessera::procedural
