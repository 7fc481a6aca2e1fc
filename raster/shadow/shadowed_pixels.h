// Comparing shadow methods on finished frames, as a viewer sees them. A pixel is shadowed by
// a method where its luma is more than `levels` levels darker than in the same frame
// rendered without shadows; luma is Rec. 709's weighting (0.2126, 0.7152, 0.0722) of the
// 8-bit sRGB-encoded R, G and B (levels 0 .. 255). The disagreement of two methods is the
// fraction of the pixels shadowed by either where only one of them shadows.
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

#include "raster/core/frame.h"

namespace tessera::shadow {

struct ShadowDisagreement {
    size_t shadowed_a = 0;  // pixels shadowed in frame a
    size_t shadowed_b = 0;
    size_t either = 0;      // shadowed in a or b
    size_t differ = 0;      // shadowed in exactly one of them
    double fraction() const { return either ? double(differ) / double(either) : 0.0; }
};

// Per pixel, 1 where `shadowed` is more than `levels` darker than `unshadowed`, else 0.
// Throws std::invalid_argument when the sizes differ.
std::vector<uint8_t> shadowed_pixels(const Frame& unshadowed, const Frame& shadowed, float levels = 8.0f);

// Throws std::invalid_argument when the sizes differ.
ShadowDisagreement compare_shadowed_pixels(const Frame& unshadowed, const Frame& a, const Frame& b,
                                           float levels = 8.0f);

}  // namespace tessera::shadow
