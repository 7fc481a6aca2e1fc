// The radiance of a scene's background along a ray: the full-screen environment pass of
// ray-marching renderers. The ray direction of a pixel is the camera's:
// d = u * x_ndc / P00 + v * y_ndc / P11 - w (the inverse of the view and projection matrices,
// "rayDirMatrix", restricted to directions).
//
// Two forms: one direction (the reference, and what reflections look up), and kLanes
// directions at once for the per-pixel background passes. The sky is one template over float
// and simd::vfloat, so the lane form equals the one-direction form bit for bit at every lane
// width; a cube map is sampled one lane at a time.
#pragma once
#include <glm/glm.hpp>

#include <algorithm>
#include <cstdint>

#include "raster/core/tile.h"
#include "raster/scene/background.h"
#include "raster/simd/lane_math.h"

namespace tessera::shade {

// Radiance seen along `direction` (any length; zero, infinite or NaN gives (0, 0, -1)).
glm::vec3 background_radiance(const scene::Background& background, glm::vec3 direction);

// The same along kLanes directions (one per lane), equal lane by lane to the form above.
simd::V3<simd::vfloat> background_radiance_lanes(const scene::Background& background,
                                                 const simd::V3<simd::vfloat>& direction);

// Writes the background into the pixels of `tile` that `empty` picks, kLanes pixels of a row
// at a time: `empty(x0, y, n)` gives the mask of the pixels x0 + i (i < n) to fill, and
// `radiance(x0, y)` the colours of pixels x0 .. x0 + kLanes - 1 (asked only for groups that
// hold an empty pixel), alpha 1. The per-pixel background passes of the rasterizer
// (shade_background) and of ray marching (march::BackgroundPass) are this loop.
template <class Empty, class Radiance>
void fill_background_lanes(const Tile& tile, Empty empty, Radiance radiance) {
    constexpr int N = simd::kLanes;
    static_assert(N <= 32, "one bit per lane");
    alignas(64) float r[N], g[N], b[N];
    for (int y = tile.rect.y0; y < tile.rect.y1; ++y)
        for (int x0 = tile.rect.x0; x0 < tile.rect.x1; x0 += N) {
            const int n = std::min(N, tile.rect.x1 - x0);
            const uint32_t mask = empty(x0, y, n);
            if (!mask) continue;
            const simd::V3<simd::vfloat> c = radiance(x0, y);
            glm::vec4* out = &tile.colour_at(x0, y);
            if (mask == simd::kEveryLaneBits) {  // all of them (the open sky): the lanes interleaved as they are
                simd::store_interleaved4(&out->r, c.x, c.y, c.z, simd::vfloat(1.0f));
                continue;
            }
            c.x.store(r);
            c.y.store(g);
            c.z.store(b);
            for (int i = 0; i < n; ++i)
                if (mask >> i & 1u) out[i] = glm::vec4(r[i], g[i], b[i], 1.0f);
        }
}

// The mask of fill_background_lanes' `empty` from a per-pixel test: `whole(x0, y)` gives the
// mask of the kLanes pixels of a whole group (tested in lanes), `one(x, y)` tests a pixel of
// the group cut by the tile's right edge (whose row may end before x0 + kLanes).
template <class Whole, class One>
uint32_t empty_mask(int x0, int y, int n, Whole whole, One one) {
    if (n == simd::kLanes) return whole(x0, y);
    uint32_t mask = 0;
    for (int i = 0; i < n; ++i)
        if (one(x0 + i, y)) mask |= 1u << i;
    return mask;
}

}  // namespace tessera::shade
