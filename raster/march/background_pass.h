// The background as a compute pass (a full-screen pass that looks up the
// environment with the per-pixel ray direction, drawn "behind everything"): every pixel of the
// tile whose depth is still the cleared 1.0 gets the background's radiance along its ray. The
// opaque shading pass already paints empty pixels this way; this pass is for frames that have
// no triangles to shade (pure ray-marched scenes).
#pragma once
#include "raster/core/tile.h"
#include "raster/march/ray_generation.h"
#include "raster/shade/background_radiance.h"

namespace tessera::march {

class BackgroundPass {
public:
    // Both are borrowed and must outlive the pass.
    BackgroundPass(const RayGenerator& rays, const scene::Background& background)
        : rays_(rays), background_(background) {}

    // kLanes pixels of a row at a time (the lane forms of the rays and the radiance).
    void run(const Tile& target) const;
    // One pixel at a time through the one-ray forms: what run() is tested against.
    void run_reference(const Tile& target) const;

private:
    const RayGenerator& rays_;
    const scene::Background& background_;
};

}  // namespace tessera::march
