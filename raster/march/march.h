// The ray marcher: sample f along the ray from t0 with the step schedule of
// MarchSettings, stop at the first sample inside the solid (f >= 0), then refine the last
// bracket by bisection. Generic over any MarchField.
//
// march_ray is the scalar reference: one ray, no packets. march_packet marches kMarchLanes
// rays in lockstep with the same arithmetic per lane, evaluating the field for all lanes at
// once (see evaluate_lanes) so the field's inner loops run on vectors; lanes that have
// finished are masked, and the packet stops when every lane has. Tests compare the two.
//
// A field that bounds itself along the packet's rays (BoundedPacketField, e.g. the metaballs a
// packet crosses) is first asked which lanes can reach the surface at all, and then, before
// each run of kBoundedSteps steps, whether any active lane can within that run; when none can,
// the run's steps are taken without sampling (the same t and step updates as a run of
// outside samples), so the bound saves samples and never changes a hit.
//
// A NaN field value counts as "outside" (the comparison f >= 0 is false), so a field that
// breaks down somewhere yields a miss there, never a crash or a NaN depth.
#pragma once
#include <glm/glm.hpp>

#include <algorithm>
#include <cstdint>
#include <limits>

#include "raster/march/march_field.h"
#include "raster/march/march_settings.h"
#include "raster/march/ray_packet.h"
#include "raster/simd/simd.h"

namespace tessera::march {

inline constexpr float kMiss = std::numeric_limits<float>::infinity();

// Steps a bounded field (BoundedPacketField) is asked to rule out at once: on the metaballs
// scene, 8 takes fewer samples plus bounds (each about one sample's cost) than 4 or 16.
inline constexpr int kBoundedSteps = 8;

namespace detail {
// Bisection on [outside, inside] (f < 0 at outside, f >= 0 at inside) until the bracket is no
// wider than the tolerance or cannot shrink in float; returns the midpoint.
template <MarchField F>
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
template <MarchField F>
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
// The per-lane state is one simd::vfloat per quantity and the lane bookkeeping is masks; only
// the field is called through arrays (evaluate_lanes), since fields choose their own SIMD.
template <MarchField F>
void march_packet(const F& field, const RayPacket& rays, const PacketSegments& segments,
                  const MarchSettings& settings, float* t_hit) {
    using simd::vfloat;
    using simd::vmask;
    constexpr int N = kMarchLanes;
    alignas(64) float first_step[N], growth_of[N], px[N], py[N], pz[N], v[N];
    const double steps_sum = settings.steps_sum();
    for (int i = 0; i < N; ++i) {
        t_hit[i] = kMiss;
        const Interval segment{segments.t0[i], segments.t1[i]};
        const MarchSettings::Schedule s =
            segment.empty() ? MarchSettings::Schedule{0.0f, 1.0f} : settings.schedule(segment, steps_sum);
        first_step[i] = s.first_step;
        growth_of[i] = s.growth;
    }
    const vfloat t0 = vfloat::load(segments.t0), t1 = vfloat::load(segments.t1);
    const vfloat ox = vfloat::load(rays.ox), oy = vfloat::load(rays.oy), oz = vfloat::load(rays.oz);
    const vfloat dx = vfloat::load(rays.dx), dy = vfloat::load(rays.dy), dz = vfloat::load(rays.dz);
    const vfloat growth = vfloat::load(growth_of);
    vmask active = (simd::lane_index() < simd::vint(rays.count)) & (t0 <= t1);
    // A lane the field rules out over its whole segment misses without a sample.
    if constexpr (BoundedPacketField<F>) active = active & field.may_reach(t0, t1);
    if (!simd::any(active)) return;

    // Sample at t0 first: a lane that starts inside the solid hits there.
    (ox + dx * t0).store(px);
    (oy + dy * t0).store(py);
    (oz + dz * t0).store(pz);
    evaluate_lanes(field, px, py, pz, v);
    const vmask starts_inside = active & (vfloat(0.0f) <= vfloat::load(v));
    for (int i = 0; i < N; ++i)
        if (simd::bits(starts_inside) >> i & 1u) t_hit[i] = segments.t0[i];
    active = simd::andnot(starts_inside, active);

    vfloat t_prev = t0, dt = vfloat::load(first_step), inside_t(0.0f);
    vmask found(false);
    for (int k = 0; k < settings.steps && simd::any(active);) {
        int run = 1;  // steps to sample one by one
        if constexpr (BoundedPacketField<F>) {
            // The next steps as the loop below would take them if every sample were outside;
            // when the field rules out every active lane's stretch [t_prev, last], that is
            // what they are, and the packet moves on without sampling them.
            run = std::min(kBoundedSteps, settings.steps - k);
            vfloat t_run = t_prev, dt_run = dt, last = t_prev;
            vmask on = active;
            for (int j = 0; j < run; ++j) {
                const vfloat t = simd::min(t_run + dt_run, t1);
                last = simd::select(on, t, last);
                on = simd::andnot(on & (t1 <= t), on);
                t_run = simd::select(on, t, t_run);
                dt_run = simd::select(on, dt_run * growth, dt_run);
            }
            if (!simd::any(active & field.may_reach(t_prev, last))) {
                active = on;
                t_prev = t_run;
                dt = dt_run;
                k += run;
                continue;
            }
        }
        for (int j = 0; j < run && simd::any(active); ++j) {
            const vfloat t = simd::min(t_prev + dt, t1);
            (ox + dx * t).store(px);
            (oy + dy * t).store(py);
            (oz + dz * t).store(pz);
            evaluate_lanes(field, px, py, pz, v);
            const vmask inside = active & (vfloat(0.0f) <= vfloat::load(v));
            const vmask left = active & (t1 <= t);  // reached the end of the bounds: a miss
            found = found | inside;
            inside_t = simd::select(inside, t, inside_t);
            active = simd::andnot(inside | left, active);
            t_prev = simd::select(active, t, t_prev);
            dt = simd::select(active, dt * growth, dt);
        }
        k += run;
    }

    // Bisection of every hit lane in lockstep, with march_ray's stopping rule per lane (bracket
    // within tolerance, or no float strictly between its ends), so each lane ends exactly where
    // the scalar bisect would.
    vfloat outside = t_prev, inside = inside_t;
    vmask bisecting = settings.refine ? found : vmask(false);
    const vfloat tolerance(settings.tolerance);
    while (true) {
        const vfloat mid = vfloat(0.5f) * (outside + inside);
        bisecting = bisecting & (tolerance < inside - outside) & (outside < mid) & (mid < inside);
        if (!simd::any(bisecting)) break;
        (ox + dx * mid).store(px);
        (oy + dy * mid).store(py);
        (oz + dz * mid).store(pz);
        evaluate_lanes(field, px, py, pz, v);
        const vmask in = vfloat(0.0f) <= vfloat::load(v);
        inside = simd::select(bisecting & in, mid, inside);
        outside = simd::select(simd::andnot(in, bisecting), mid, outside);
    }
    alignas(64) float result[N];
    (settings.refine ? vfloat(0.5f) * (outside + inside) : inside).store(result);
    const uint32_t hits = simd::bits(found);
    for (int i = 0; i < N; ++i)
        if (hits >> i & 1u) t_hit[i] = result[i];
}

}  // namespace tessera::march
