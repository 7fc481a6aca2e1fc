#include "procedural/dunes.h"

#include <algorithm>
#include <cmath>

namespace tessera::procedural {

namespace {
// The wave vector nearest to k with a whole number of waves across the tile on each axis; never
// zero (a wave longer than the tile becomes one wave across it along its main axis).
glm::vec2 snap_wave(glm::vec2 k, glm::ivec2 period) {
    const glm::vec2 waves(std::round(k.x * float(period.x)), std::round(k.y * float(period.y)));
    if (waves == glm::vec2(0.0f)) {
        const bool along_x = std::abs(k.x * float(period.x)) >= std::abs(k.y * float(period.y));
        return along_x ? glm::vec2(std::copysign(1.0f, k.x) / float(period.x), 0.0f)
                       : glm::vec2(0.0f, std::copysign(1.0f, k.y) / float(period.y));
    }
    return waves / glm::vec2(period);
}

// Lattice cells per tile for noise of `frequency` cells per input unit: whole, at least 2.
int tile_cells(float frequency, int period) {
    return int(std::clamp(std::round(double(frequency) * period), 2.0, double(1 << 20)));
}

TorusLattice tile_lattice(float frequency, glm::ivec2 period) {
    return {{tile_cells(frequency, period.x), tile_cells(frequency, period.y)}};
}
}  // namespace

DuneWaves<TorusLattice> dune_waves(const Dunes& d, glm::ivec2 period) {
    const float k = 1.0f / d.wavelength;
    const TorusLattice bend = tile_lattice(0.5f * k, period), height = tile_lattice(0.7f * k, period);
    return {snap_wave(d.wind * k, period), snap_wave(d.wind * (1.0f / d.ripple_wavelength), period),
            glm::vec2(bend.period) / glm::vec2(period), glm::vec2(height.period) / glm::vec2(period),
            bend, height};
}

}  // namespace tessera::procedural
