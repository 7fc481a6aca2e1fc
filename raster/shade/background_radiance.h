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

// Writes the background into the pixels of `tile` that `empty(x, y)` picks, kLanes pixels of
// a row at a time: `radiance(x0, y)` gives the colours of pixels x0 .. x0 + kLanes - 1 (asked
// only for groups that hold an empty pixel), alpha 1. The per-pixel background passes of the
// rasterizer (shade_background) and of ray marching (march::BackgroundPass) are this loop.
template <class Empty, class Radiance>
void fill_background_lanes(const Tile& tile, Empty empty, Radiance radiance) {
    constexpr int N = simd::kLanes;
    static_assert(N <= 32, "one bit per lane");
    alignas(64) float r[N], g[N], b[N];
    for (int y = tile.rect.y0; y < tile.rect.y1; ++y)
        for (int x0 = tile.rect.x0; x0 < tile.rect.x1; x0 += N) {
            const int n = std::min(N, tile.rect.x1 - x0);
            uint32_t mask = 0;
            for (int i = 0; i < n; ++i)
                if (empty(x0 + i, y)) mask |= 1u << i;
            if (!mask) continue;
            const simd::V3<simd::vfloat> c = radiance(x0, y);
            c.x.store(r);
            c.y.store(g);
            c.z.store(b);
            glm::vec4* out = &tile.colour_at(x0, y);
            if (n == N && mask == (N == 32 ? ~0u : (1u << N) - 1u)) {
                // All of them (the open sky): one interleaving loop, which the compiler
                // vectorises, instead of a test and a store per pixel.
                for (int i = 0; i < N; ++i) out[i] = glm::vec4(r[i], g[i], b[i], 1.0f);
                continue;
            }
            for (int i = 0; i < n; ++i)
                if (mask >> i & 1u) out[i] = glm::vec4(r[i], g[i], b[i], 1.0f);
        }
}

}  // namespace tessera::shade
