// Initial conditions for reaction-diffusion: everywhere A = 1, B = 0 (the trivial steady
// state), seeded with patches of Pearson's (A, B) = (1/2, 1/4) from which patterns grow.
// Deterministic from a seed (hash.h), independent of thread count.
#pragma once
#include <cstdint>

#include "procedural/grid.h"
#include "procedural/reaction_diffusion.h"

namespace tessera::procedural {

// `count` discs of radius `radius` cells at hashed positions (they wrap around the edges).
// count <= 0 picks one disc per 64x64 cells.
RdState rd_initial_spots(int width, int height, uint32_t seed, int count = 0, int radius = 4);

// Patches where smooth value noise (feature size ~`scale` cells) exceeds a threshold.
RdState rd_initial_noise(int width, int height, uint32_t seed, float scale = 16.0f);

// From an image with values in [0, 1] (e.g. a logo): v = 1 seeds Pearson's patch, 0 nothing;
// (A, B) = (1 - v/2, v/4). Non-finite values are rejected.
RdState rd_initial_image(const Grid& image);

}  // namespace tessera::procedural
