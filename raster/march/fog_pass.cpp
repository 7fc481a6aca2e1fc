#include "raster/march/fog_pass.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
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

// Fog::apply's t L + (1 - t) C on channels 0..2 of the n pixels of an RGBA row whose
// coverage is non-zero (all of them without coverage); alpha and other pixels are left alone.
// Plain loops over restrict pointers that GCC vectorises (the colour's channels as
// interleaved loads and stores, the coverage as a mask), with the float operations of the
// one-pixel form in its order.
void apply_fog(float* __restrict rgba, const uint8_t* __restrict coverage, const float* __restrict t0,
               const float* __restrict t1, const float* __restrict t2, const glm::vec3 colour, int n) {
    if (!coverage) {
        for (int i = 0; i < n; ++i) {
            float* c = rgba + 4 * i;
            c[0] = t0[i] * c[0] + (1.0f - t0[i]) * colour.r;
            c[1] = t1[i] * c[1] + (1.0f - t1[i]) * colour.g;
            c[2] = t2[i] * c[2] + (1.0f - t2[i]) * colour.b;
        }
        return;
    }
    for (int i = 0; i < n; ++i) {
        if (!coverage[i]) continue;
        float* c = rgba + 4 * i;
        c[0] = t0[i] * c[0] + (1.0f - t0[i]) * colour.r;
        c[1] = t1[i] * c[1] + (1.0f - t1[i]) * colour.g;
        c[2] = t2[i] * c[2] + (1.0f - t2[i]) * colour.b;
    }
}

}  // namespace

void FogPass::run(const Tile& target) const {
    if (!fog_.enabled()) return;
    using simd::vfloat;
    constexpr int N = simd::kLanes;
    alignas(64) float depth[N], t[3][N];
    const glm::vec3 eye = rays_.eye();
    for (int y = target.rect.y0; y < target.rect.y1; ++y) {
        // The row's depths, coverage and colours are contiguous from the tile's first column.
        const float* depth_row = &target.depth_at(target.rect.x0, y);
        const uint8_t* coverage_row = target.coverage ? target.coverage + target.offset(target.rect.x0, y) : nullptr;
        float* colour_row = &target.colour_at(target.rect.x0, y).r;
        for (int x0 = target.rect.x0; x0 < target.rect.x1; x0 += N) {
            const int from = x0 - target.rect.x0, n = std::min(N, target.rect.x1 - x0);
            const uint8_t* coverage = coverage_row ? coverage_row + from : nullptr;
            if (coverage && std::all_of(coverage, coverage + n, [](uint8_t c) { return c == 0; })) continue;
            // Lanes past the row's end see the cleared depth; their results are not stored.
            for (int i = 0; i < N; ++i) depth[i] = i < n ? depth_row[from + i] : 1.0f;
            const simd::V3<vfloat> d = rays_.directions(x0, y);
            const vfloat distance = rays_.distances_from_depth(x0, y, vfloat::load(depth));
            const vfloat far = rays_.far_distances(d);
            const vfloat visible = far_visibility(distance, far);
            const simd::V3<vfloat> tr = fog_.transmittance(eye, d.y, distance);
            (tr.x * visible).store(t[0]);
            (tr.y * visible).store(t[1]);
            (tr.z * visible).store(t[2]);
            apply_fog(colour_row + 4 * size_t(from), coverage, t[0], t[1], t[2], fog_.colour, n);
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
