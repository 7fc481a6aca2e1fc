// Named Gray-Scott parameter sets (feed f, kill k) for the classic pattern classes, all for
// Karl Sims' convention (Da = 1, Db = 0.5, dt = 1, his 3x3 Laplacian). The pattern class
// depends on f, k and the ratio Da/Db = 2; the diffusion scale only sets the pattern size.
#pragma once
#include <span>
#include <string>
#include <string_view>

namespace tessera::procedural {

struct RdPreset {
    std::string_view name;
    float feed;
    float kill;
    std::string_view pattern;  // what it grows into, and where the values come from
};

std::span<const RdPreset> rd_presets();

// The preset called `name`, or null.
const RdPreset* find_rd_preset(std::string_view name);

// "spots, stripes, ..." for error messages.
std::string rd_preset_names();

}  // namespace tessera::procedural
