#include "raster/march/background_pass.h"

namespace tessera::march {

void BackgroundPass::run(const Tile& target) const {
    // Pixels nothing was drawn in: depth not below 1 (NaN included).
    const auto one = [&](int x, int y) { return !(target.depth_at(x, y) < 1.0f); };
    const auto whole = [&](int x0, int y) {
        const simd::vfloat depth = simd::vfloat::load_unaligned(&target.depth_at(x0, y));
        return simd::bits(simd::andnot(depth < simd::vfloat(1.0f), simd::vmask(true)));
    };
    shade::fill_background_lanes(
        target, [&](int x0, int y, int n) { return shade::empty_mask(x0, y, n, whole, one); },
        [&](int x0, int y) { return shade::background_radiance_lanes(background_, rays_.directions(x0, y)); });
}

void BackgroundPass::run_reference(const Tile& target) const {
    for (int y = target.rect.y0; y < target.rect.y1; ++y)
        for (int x = target.rect.x0; x < target.rect.x1; ++x)
            if (!(target.depth_at(x, y) < 1.0f))
                target.colour_at(x, y) = glm::vec4(shade::background_radiance(background_, rays_.direction(x, y)), 1.0f);
}

}  // namespace tessera::march
