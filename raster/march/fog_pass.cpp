#include "raster/march/fog_pass.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace tessera::march {

FogPass::FogPass(const RayGenerator& rays, const Fog& fog) : rays_(rays), fog_(fog) {
    fog_.validate();
}

namespace {

constexpr float kFarFadeStart = 0.75f;  // of the far distance

// 1 up to kFarFadeStart of the far distance, 0 at the far plane, smooth between. The
// background (infinitely far) keeps the closed form: high fog seen upwards lets the sky through.
float far_visibility(float distance, float far_distance) {
    if (std::isinf(distance)) return 1.0f;
    if (!(distance < far_distance)) return 0.0f;
    return 1.0f - glm::smoothstep(kFarFadeStart, 1.0f, distance / far_distance);
}

// far_visibility for kLanes distances, far_distance(d) being far / dot(d, forward).
simd::vfloat far_visibility(simd::vfloat distance, simd::vfloat far_distance) {
    using simd::vfloat;
    const vfloat fade = vfloat(1.0f) - simd::smoothstep(kFarFadeStart, 1.0f, distance / far_distance);
    const vfloat visible = simd::select(distance < far_distance, fade, vfloat(0.0f));
    return simd::select(vfloat(std::numeric_limits<float>::infinity()) <= distance, vfloat(1.0f), visible);
}

}  // namespace

void FogPass::run(const Tile& target) const {
    if (!fog_.enabled()) return;
    using simd::vfloat;
    constexpr int N = simd::kLanes;
    static_assert(N <= 32, "one bit per lane");
    alignas(64) float depth[N], t[3][N];
    const glm::vec3 eye = rays_.eye(), colour = fog_.colour;
    for (int y = target.rect.y0; y < target.rect.y1; ++y)
        for (int x0 = target.rect.x0; x0 < target.rect.x1; x0 += N) {
            const int n = std::min(N, target.rect.x1 - x0);
            uint32_t active = 0;
            for (int i = 0; i < N; ++i) {
                depth[i] = i < n ? target.depth_at(x0 + i, y) : 1.0f;
                if (i < n && target.active(x0 + i, y)) active |= 1u << i;
            }
            if (!active) continue;
            const simd::V3<vfloat> d = rays_.directions(x0, y);
            const vfloat distance = rays_.distances_from_depth(x0, y, vfloat::load(depth));
            const vfloat far = rays_.far_distances(d);
            const vfloat visible = far_visibility(distance, far);
            const simd::V3<vfloat> tr = fog_.transmittance(eye, d.y, distance);
            (tr.x * visible).store(t[0]);
            (tr.y * visible).store(t[1]);
            (tr.z * visible).store(t[2]);
            for (int i = 0; i < n; ++i) {
                if (!(active >> i & 1u)) continue;
                // Fog::apply's t L + (1 - t) C per channel.
                glm::vec4& c = target.colour_at(x0 + i, y);
                c = glm::vec4(t[0][i] * c.r + (1.0f - t[0][i]) * colour.r, t[1][i] * c.g + (1.0f - t[1][i]) * colour.g,
                              t[2][i] * c.b + (1.0f - t[2][i]) * colour.b, c.a);
            }
        }
}

void FogPass::run_reference(const Tile& target) const {
    if (!fog_.enabled()) return;
    for (int y = target.rect.y0; y < target.rect.y1; ++y)
        for (int x = target.rect.x0; x < target.rect.x1; ++x) {
            if (!target.active(x, y)) continue;
            glm::vec4& c = target.colour_at(x, y);
            const glm::vec3 d = rays_.direction(x, y);
            const float distance = rays_.distance_from_depth(x, y, target.depth_at(x, y));
            const glm::vec3 t = fog_.transmittance(rays_.eye(), d, distance) *
                                far_visibility(distance, rays_.far_distance(d));
            c = glm::vec4(t * glm::vec3(c) + (1.0f - t) * fog_.colour, c.a);
        }
}

}  // namespace tessera::march
