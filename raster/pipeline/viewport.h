// The viewport: window size, the mapping from clip space to window coordinates (top-down
// rows, pixel centres at +0.5, window depth z_ndc * 0.5 + 0.5, see camera.h) and the guard
// band derived from the fixed-point limits (fixed_point.h).
//
// The mapping is written once as a template over float and simd::vfloat so that the SIMD
// vertex stage and the scalar clipper/reference produce bit-identical window coordinates
// (the library builds with -ffp-contract=off so no compiler-chosen FMA breaks that).
#pragma once
#include <cstdint>
#include <stdexcept>
#include <string>

#include "raster/pipeline/fixed_point.h"

namespace tessera::pipeline {

struct Viewport {
    int width = 0;
    int height = 0;
    float half_width = 0.0f;
    float half_height = 0.0f;
    // Clip-space guard band: |x| <= guard_x * w and |y| <= guard_y * w map to window
    // coordinates within [-kCoordLimit, kCoordLimit].
    float guard_x = 0.0f;
    float guard_y = 0.0f;

    Viewport(int w, int h) : width(w), height(h) {
        if (w < 1 || h < 1 || w > kMaxViewport || h > kMaxViewport)
            throw std::invalid_argument("viewport " + std::to_string(w) + "x" + std::to_string(h) +
                                        " is outside 1x1 .. " + std::to_string(kMaxViewport) + "x" +
                                        std::to_string(kMaxViewport));
        half_width = 0.5f * float(w);
        half_height = 0.5f * float(h);
        // (ndc + 1) * W/2 <= L  <=>  ndc <= 2L/W - 1, and symmetrically -L <= (ndc + 1) * W/2.
        guard_x = 2.0f * kCoordLimit / float(w) - 1.0f;
        guard_y = 2.0f * kCoordLimit / float(h) - 1.0f;
    }

    // Window position of a clip-space point with w > 0: x to the right, y down, in pixels.
    template <class F>
    void to_window(F cx, F cy, F cz, F cw, F& wx, F& wy, F& wz) const {
        const F inv_w = F(1.0f) / cw;
        wx = (cx * inv_w + F(1.0f)) * F(half_width);
        wy = (F(1.0f) - cy * inv_w) * F(half_height);
        wz = cz * inv_w * F(0.5f) + F(0.5f);
    }
};

}  // namespace tessera::pipeline
