// How a frame too large for one pass is cut (README "Frames beyond one pass"): bands of whole
// rows, top to bottom, each rendered as regions side by side (camera.h region()). A band is
// the unit that is streamed to the file and handed to an MPI rank; a region is the unit the
// rasterizer renders, so it stays within the fixed-point viewport limit (fixed_point.h).
//
// The layout depends on the frame size alone, never on the thread or rank count, so every
// process renders a band to the same bytes.
#pragma once
#include <algorithm>
#include <cstdint>
#include <utility>

#include "raster/pipeline/fixed_point.h"

namespace tessera::render {

struct BandLayout {
    int width = 0, height = 0;  // the whole frame
    int band_rows = 0;          // rows per band (the last band may have fewer)
    int region_width = 0;       // columns per region (the last region may have fewer)

    int bands() const { return (height + band_rows - 1) / band_rows; }
    // Rows [first, second) of band b.
    std::pair<int, int> rows(int band) const {
        return {band * band_rows, std::min(height, (band + 1) * band_rows)};
    }
};

// Frames larger than one viewport either way are rendered in bands.
inline bool needs_bands(int width, int height) { return width > pipeline::kMaxViewport || height > pipeline::kMaxViewport; }

// The layout tessera uses: about 4 M pixels per band (64 MiB of float RGBA, plus the
// visibility of one region), rows a multiple of 128 (the raster tile and the 64-pixel file
// tiles divide it, so no tile straddles two bands), regions as wide as the viewport allows.
inline BandLayout band_layout(int width, int height) {
    constexpr int64_t kBandPixels = int64_t(1) << 22;
    constexpr int kRowAlign = 128;
    const int64_t rows = std::clamp<int64_t>(kBandPixels / std::max(width, 1) / kRowAlign * kRowAlign, kRowAlign,
                                             pipeline::kMaxViewport);
    return {width, height, int(std::min<int64_t>(rows, std::max(height, 1))), std::min(width, pipeline::kMaxViewport)};
}

}  // namespace tessera::render
