// The ray marcher (seeds/003): sample f along the ray from t0 with the step schedule of
// MarchSettings, stop at the first sample inside the solid (f >= 0), then refine the last
// bracket by bisection. Generic over any ImplicitField.
//
// march_ray is the scalar reference: one ray, no packets. march_packet marches kMarchLanes
// rays in lockstep with the same arithmetic per lane, evaluating the field for all lanes at
// once (see evaluate_lanes) so the field's inner loops run on vectors; lanes that have
// finished are masked, and the packet stops when every lane has. Tests compare the two.
//
// A NaN field value counts as "outside" (the comparison f >= 0 is false), so a field that
// breaks down somewhere yields a miss there, never a crash or a NaN depth.
#pragma once
#include <glm/glm.hpp>

#include <algorithm>
#include <limits>

#include "raster/march/implicit_field.h"
#include "raster/march/march_settings.h"
#include "raster/march/ray_packet.h"

namespace tessera::march {

inline constexpr float kMiss = std::numeric_limits<float>::infinity();

namespace detail {
// Bisection on [outside, inside] (f < 0 at outside, f >= 0 at inside) until the bracket is no
// wider than the tolerance or cannot shrink in float; returns the midpoint.
template <ImplicitField F>
float bisect(const F& field, glm::vec3 o, glm::vec3 d, float outside, float inside,
             float tolerance) {
    while (inside - outside > tolerance) {
        const float mid = 0.5f * (outside + inside);
        if (mid <= outside || mid >= inside) break;
        if (field.value(o + d * mid) >= 0.0f)
            inside = mid;
        else
            outside = mid;
    }
    return 0.5f * (outside + inside);
}
}  // namespace detail

// The first surface crossing of the ray o + t d (|d| = 1) within `segment`, or kMiss.
// `settings` must have been validated.
template <ImplicitField F>
float march_ray(const F& field, glm::vec3 o, glm::vec3 d, Interval segment,
                const MarchSettings& settings) {
    if (segment.empty()) return kMiss;
    if (field.value(o + d * segment.t0) >= 0.0f) return segment.t0;  // starts inside
    const MarchSettings::Schedule schedule = settings.schedule(segment);
    float t_prev = segment.t0;
    float dt = schedule.first_step;
    for (int k = 0; k < settings.steps; ++k) {
        const float t = std::min(t_prev + dt, segment.t1);
        if (field.value(o + d * t) >= 0.0f)
            return settings.refine ? detail::bisect(field, o, d, t_prev, t, settings.tolerance) : t;
        if (t >= segment.t1) break;
        t_prev = t;
        dt *= schedule.growth;
    }
    return kMiss;
}

// Per-lane bounding intervals of a packet (t0 > t1: the lane misses the bounds).
struct PacketSegments {
    alignas(64) float t0[kMarchLanes];
    alignas(64) float t1[kMarchLanes];
};

// Marches every live lane of `rays`; t_hit[i] receives what march_ray would return for lane i.
template <ImplicitField F>
void march_packet(const F& field, const RayPacket& rays, const PacketSegments& segments,
                  const MarchSettings& settings, float* t_hit) {
    constexpr int N = kMarchLanes;
    alignas(64) float t_prev[N], dt[N], growth[N], t[N], px[N], py[N], pz[N], v[N];
    alignas(64) int active[N];  // -1 (all bits) while the lane still marches, else 0
    int live = 0;
    for (int i = 0; i < N; ++i) {
        t_hit[i] = kMiss;
        const Interval segment{segments.t0[i], segments.t1[i]};
        active[i] = (i < rays.count && !segment.empty()) ? -1 : 0;
        const MarchSettings::Schedule s =
            active[i] ? settings.schedule(segment) : MarchSettings::Schedule{0.0f, 1.0f};
        t_prev[i] = active[i] ? segment.t0 : 0.0f;
        dt[i] = s.first_step;
        growth[i] = s.growth;
        live -= active[i];
    }
    if (live == 0) return;

    // Sample at t0 first: a lane that starts inside the solid hits there.
    for (int i = 0; i < N; ++i) {
        px[i] = rays.ox[i] + rays.dx[i] * t_prev[i];
        py[i] = rays.oy[i] + rays.dy[i] * t_prev[i];
        pz[i] = rays.oz[i] + rays.dz[i] * t_prev[i];
    }
    evaluate_lanes(field, px, py, pz, v);
    alignas(64) float inside_t[N];  // the first inside sample, for refinement
    alignas(64) int found[N];
    for (int i = 0; i < N; ++i) {
        found[i] = 0;
        inside_t[i] = 0.0f;
        if (active[i] && v[i] >= 0.0f) {
            t_hit[i] = t_prev[i];
            active[i] = 0;
            --live;
        }
    }

    for (int k = 0; k < settings.steps && live > 0; ++k) {
        for (int i = 0; i < N; ++i) {
            t[i] = std::min(t_prev[i] + dt[i], segments.t1[i]);
            px[i] = rays.ox[i] + rays.dx[i] * t[i];
            py[i] = rays.oy[i] + rays.dy[i] * t[i];
            pz[i] = rays.oz[i] + rays.dz[i] * t[i];
        }
        evaluate_lanes(field, px, py, pz, v);
        // Branch-free lane update on all-ones / zero int masks (no && or ifs, which GCC
        // cannot if-convert), so it vectorises like the rest.
        live = 0;
        for (int i = 0; i < N; ++i) {
            const int inside = active[i] & -int(v[i] >= 0.0f);
            const int left = active[i] & -int(t[i] >= segments.t1[i]);  // a miss
            const int still = active[i] & ~inside & ~left;
            found[i] |= inside;
            inside_t[i] = inside ? t[i] : inside_t[i];
            active[i] = still;
            t_prev[i] = still ? t[i] : t_prev[i];
            dt[i] = still ? dt[i] * growth[i] : dt[i];
            live -= still;
        }
    }

    for (int i = 0; i < N; ++i) {
        if (!found[i]) continue;
        t_hit[i] = settings.refine ? detail::bisect(field, rays.origin(i), rays.direction(i),
                                                    t_prev[i], inside_t[i], settings.tolerance)
                                   : inside_t[i];
    }
}

}  // namespace tessera::march
