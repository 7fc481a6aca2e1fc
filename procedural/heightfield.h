// Heightfield terrain as an image: h(x, y) over a width x height grid from the reliefs of
// fractal.h (fBm, ridged multifractal, domain-warped fBm, dunes), parallel over rows with
// oneTBB and vectorised over x (the batch forms of fractal_batch.h and dunes.h). Deterministic
// from the seed whatever the thread count: every cell is a pure function of its coordinates.
#pragma once
#include <cstdint>

#include "procedural/field.h"
#include "procedural/grid.h"

namespace tessera::procedural {

struct HeightfieldParams {
    Relief relief = Relief::fbm;
    Fractal fractal{8, 2.0f, 0.5f, 0};
    int cells = 4;         // octave-0 lattice cells across the width (feature size = width/cells)
    bool tileable = true;  // every lattice and wave repeats over the map, so it wraps seamlessly
    float warp = 0.4f;     // Relief::warped amount, in octave-0 cells
    Dunes dunes{};         // Relief::dunes (wavelength in octave-0 cells)
};

// Heights in [0, 1] for fbm, ridged and warped relief (about [0, 1.02] for dunes), not rescaled,
// so a tile and its neighbour keep matching levels. Throws std::invalid_argument on bad sizes
// or parameters (octaves outside 1..24, cells < 1, a tileable fbm, ridged or warped map with a
// fractional lacunarity). A tileable map's right edge continues into its left and its bottom
// into its top, for every relief: fbm, ridged and warped sum noise on a TorusLattice of
// cells x cells_y, and dunes snap their waves to whole counts across the map (dune_waves with a
// period), so a dune map's crests and ripples may turn and stretch slightly from the request.
Grid generate_heightfield(int width, int height, const HeightfieldParams& params);

// Rescales in place so the lowest height becomes 0 and the highest 1 (a flat map becomes 0).
// Exact min/max are order-independent, so this stays deterministic.
void normalize_heights(Grid& heights);

}  // namespace tessera::procedural
