// Reaction-diffusion as a texture: the difference A - B (1 where nothing grew, towards 0 in
// the pattern) through a colour ramp, as 8-bit RGB ready for an image writer.
#pragma once
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "procedural/reaction_diffusion.h"

namespace tessera::procedural {

struct ColorStop {
    float position;                 // in [0, 1], increasing along the ramp
    std::array<float, 3> rgb;       // linear [0, 1]
};

// Dark pattern on a pale background (pattern = low A - B): a snake-skin ramp.
std::span<const ColorStop> default_rd_ramp();

// width * height * 3 bytes, rows top to bottom. Parallel over rows; deterministic.
std::vector<uint8_t> rd_colorize(const RdState& state,
                                 std::span<const ColorStop> ramp = default_rd_ramp());

}  // namespace tessera::procedural
