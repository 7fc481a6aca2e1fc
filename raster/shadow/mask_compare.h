// Comparing two shadow methods pixel by pixel: the fraction of covered pixels whose lit /
// shadowed state (for every light) is the same, and a diff image that shows where they differ.
//
// "Non-grazing geometry": near a light's terminator (the light almost in the surface's plane)
// any depth-based method must disagree with exact rays, so the comparison can leave out the
// pixels grazing_lights() marks, as the issue's <= 1% target asks.
#pragma once
#include <filesystem>
#include <span>

#include "raster/shadow/light_mask.h"

namespace tessera::shadow {

struct MaskAgreement {
    size_t compared = 0;     // covered pixels, minus the excluded ones
    size_t excluded = 0;     // covered pixels left out (grazing)
    size_t differ = 0;       // compared pixels whose masks differ
    size_t only_a_lit = 0;   // ... where some light reaches the point in `a` but not in `b`
    size_t only_b_lit = 0;   // ... and the reverse (a pixel can count in both)
    double agreement() const { return compared ? 1.0 - double(differ) / double(compared) : 1.0; }
};

// Compares the masks over pixels that `visibility` covers and `exclude` (same size, or empty)
// leaves at 0. Throws std::invalid_argument when the sizes differ.
MaskAgreement compare_light_masks(const LightMask& a, const LightMask& b,
                                  const VisibilityBuffer& visibility,
                                  const LightMask* exclude = nullptr);

// A LightTest marking lights that graze the surface: 0 < cos(normal, to light) < max_cosine.
LightTest grazing_lights(float max_cosine);

// Writes an RGB image (format from the extension): black where nothing is covered; where the
// masks agree, light grey if some light reaches the point and dark grey if none does; red
// where only `a` lets some light through, blue where only `b` does (magenta: both, for
// different lights); olive where the pixel was excluded. Throws tessera::Error.
void write_mask_diff(const std::filesystem::path& path, const LightMask& a, const LightMask& b,
                     const VisibilityBuffer& visibility, const LightMask* exclude = nullptr);

}  // namespace tessera::shadow
