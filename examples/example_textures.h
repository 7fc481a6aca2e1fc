// Procedural textures for the example scenes: the procedural library's grids and normal maps
// turned into tessera::Texture (rows flipped so that v = 0 is the bottom, see texture.h).
#pragma once
#include <cstdint>

#include "procedural/grid.h"
#include "raster/texture/texture.h"

namespace tessera::examples {

// A tileable reaction-diffusion skin (Karl Sims' Gray-Scott, `preset` from rd_presets),
// `size` x `size`, coloured with the library's snake-skin ramp. Linear colours.
Texture reaction_diffusion_texture(const char* preset, int size, int steps, uint32_t seed);

// A tileable fBm heightfield, `size` x `size`, heights in [0, 1].
procedural::Grid heightfield_grid(int size, uint32_t seed, int cells);

// The tangent-space normal map of `heights` (seeds/004's height map -> normal map).
Texture normal_map_texture(const procedural::Grid& heights, float strength);

}  // namespace tessera::examples
