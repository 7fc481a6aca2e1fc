#include "procedural/rd_color.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace tessera::procedural {

std::span<const ColorStop> default_rd_ramp() {
    static constexpr std::array kRamp{
        ColorStop{0.0f, {0.05f, 0.04f, 0.02f}},  ColorStop{0.25f, {0.20f, 0.12f, 0.04f}},
        ColorStop{0.55f, {0.55f, 0.42f, 0.15f}}, ColorStop{0.8f, {0.85f, 0.78f, 0.50f}},
        ColorStop{1.0f, {0.95f, 0.93f, 0.80f}},
    };
    return kRamp;
}

std::vector<uint8_t> rd_colorize(const RdState& state, std::span<const ColorStop> ramp) {
    if (ramp.empty()) throw std::invalid_argument("colour ramp has no stops");
    const int w = state.a.width, h = state.a.height;
    std::vector<uint8_t> rgb(size_t(w) * size_t(h) * 3);
    tbb::parallel_for(tbb::blocked_range<int>(0, h, 16), [&](const tbb::blocked_range<int>& rows) {
        for (int y = rows.begin(); y < rows.end(); ++y) {
            const float* a = state.a.row(y);
            const float* b = state.b.row(y);
            uint8_t* out = rgb.data() + size_t(y) * size_t(w) * 3;
            for (int x = 0; x < w; ++x) {
                const float t = std::clamp(a[x] - b[x], 0.0f, 1.0f);
                size_t i = 1;
                while (i < ramp.size() && ramp[i].position < t) ++i;
                std::array<float, 3> c = ramp.back().rgb;
                if (i < ramp.size()) {
                    const ColorStop& lo = ramp[i - 1];
                    const ColorStop& hi = ramp[i];
                    const float span = hi.position - lo.position;
                    const float u = span > 0 ? std::clamp((t - lo.position) / span, 0.0f, 1.0f) : 1.0f;
                    for (int k = 0; k < 3; ++k) c[k] = lo.rgb[k] + (hi.rgb[k] - lo.rgb[k]) * u;
                }
                for (int k = 0; k < 3; ++k)
                    out[size_t(x) * 3 + k] = uint8_t(std::lround(std::clamp(c[k], 0.0f, 1.0f) * 255.0f));
            }
        }
    });
    return rgb;
}

}  // namespace tessera::procedural
