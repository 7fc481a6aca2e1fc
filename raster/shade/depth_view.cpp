#include "raster/shade/depth_view.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace tessera::shade {

void depth_view(const VisibilityBuffer& visibility, const Camera& camera, std::vector<uint8_t>& rgb8) {
    const size_t pixels = size_t(visibility.width) * size_t(visibility.height);
    rgb8.assign(pixels * 3, 0);
    const double n = camera.near, f = camera.far;
    const auto distance = [&](float window_depth) {
        const double z_ndc = 2.0 * double(window_depth) - 1.0;
        return 2.0 * n * f / (f + n - z_ndc * (f - n));
    };
    double nearest = std::numeric_limits<double>::infinity(), farthest = -nearest;
    for (size_t i = 0; i < pixels; ++i)
        if (visibility.triangle[i] != kNoTriangle) {
            const double d = distance(visibility.depth[i]);
            nearest = std::min(nearest, d);
            farthest = std::max(farthest, d);
        }
    if (!(nearest <= farthest)) return;  // nothing covered
    const double span = farthest - nearest;
    for (size_t i = 0; i < pixels; ++i) {
        if (visibility.triangle[i] == kNoTriangle) continue;
        const double t = span > 0.0 ? (distance(visibility.depth[i]) - nearest) / span : 0.0;
        const auto grey = uint8_t(std::lround(255.0 - t * (255.0 - kFarGrey)));
        rgb8[3 * i] = rgb8[3 * i + 1] = rgb8[3 * i + 2] = grey;
    }
}

}  // namespace tessera::shade
