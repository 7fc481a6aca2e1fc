#include "raster/march/background_pass.h"

#include <algorithm>

namespace tessera::march {

void BackgroundPass::run(const Tile& target) const {
    constexpr int N = simd::kLanes;
    static_assert(N <= 32, "one bit per lane");
    alignas(64) float r[N], g[N], b[N];
    for (int y = target.rect.y0; y < target.rect.y1; ++y)
        for (int x0 = target.rect.x0; x0 < target.rect.x1; x0 += N) {
            const int n = std::min(N, target.rect.x1 - x0);
            uint32_t empty = 0;
            for (int i = 0; i < n; ++i)
                if (!(target.depth_at(x0 + i, y) < 1.0f)) empty |= 1u << i;
            if (!empty) continue;
            const simd::V3<simd::vfloat> c = shade::background_radiance_lanes(background_, rays_.directions(x0, y));
            c.x.store(r);
            c.y.store(g);
            c.z.store(b);
            for (int i = 0; i < n; ++i)
                if (empty >> i & 1u) target.colour_at(x0 + i, y) = glm::vec4(r[i], g[i], b[i], 1.0f);
        }
}

void BackgroundPass::run_reference(const Tile& target) const {
    for (int y = target.rect.y0; y < target.rect.y1; ++y)
        for (int x = target.rect.x0; x < target.rect.x1; ++x)
            if (!(target.depth_at(x, y) < 1.0f))
                target.colour_at(x, y) = glm::vec4(shade::background_radiance(background_, rays_.direction(x, y)), 1.0f);
}

}  // namespace tessera::march
