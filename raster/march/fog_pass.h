// Fog as the last per-pixel compute pass of a tile ("evaluate the formula at the end
// of the pass; the background is infinitely far"): for every pixel the distance to what it
// shows is rebuilt from the depth buffer (rasterized triangles and marched surfaces alike;
// infinity where the depth is the cleared 1.0), and the colour becomes
// T colour + (1 - T) fog colour with the closed-form transmittance of fog.h.
//
// In fog the far plane is where sight ends: over the last quarter of the far distance (along
// each pixel's ray) T is faded to 0 by a smoothstep, so whatever the far plane cuts (marched
// terrain, a clipped mesh) melts into the fog instead of ending at a hard edge, and the
// surfaces a coarse march finds or misses there one pixel apart (the speckles of a distant
// ridge against the sky) all come out fog-coloured. The background keeps the closed form.
#pragma once
#include "raster/march/fog.h"
#include "raster/core/tile.h"
#include "raster/march/ray_generation.h"

namespace tessera::march {

class FogPass {
public:
    // Validates the fog (std::invalid_argument); the generator is borrowed.
    FogPass(const RayGenerator& rays, const Fog& fog);

    // kLanes pixels of a row at a time (the lane forms of ray_generation.h and fog.h).
    void run(const Tile& target) const;
    // One pixel at a time through the one-ray forms: what run() is tested against.
    void run_reference(const Tile& target) const;

private:
    const RayGenerator& rays_;
    Fog fog_;
};

}  // namespace tessera::march
