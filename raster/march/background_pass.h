// The environment as background (seeds/003: a full-screen pass that looks up the environment
// with the per-pixel ray direction, drawn "behind everything"): every pixel of the tile whose
// depth is still the cleared 1.0 gets the environment's radiance along its ray.
#pragma once
#include "raster/march/environment.h"
#include "raster/march/pass_target.h"
#include "raster/march/ray_generation.h"

namespace tessera::march {

class BackgroundPass {
public:
    // Both are borrowed and must outlive the pass.
    BackgroundPass(const RayGenerator& rays, const Environment& environment)
        : rays_(rays), environment_(environment) {}

    void run(const PassTarget& target) const;

private:
    const RayGenerator& rays_;
    const Environment& environment_;
};

}  // namespace tessera::march
