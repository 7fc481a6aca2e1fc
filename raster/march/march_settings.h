// How a ray is stepped through its bounding interval:
//
// - uniform: `steps` equal steps of min((t1 - t0) / steps, max_step). 128 steps
//   and max_step = 0.05 for its unit-thick terrain slab; max_step defaults to no cap here so
//   the march always reaches t1.
// - geometric: each step is `growth` times the previous one (+2 % is usual), the first one
//   chosen so that the steps sum exactly to t1 - t0: dt0 = (t1 - t0) (g - 1) / (g^n - 1). For
//   g = 1.02 and n = 128 that is (t1 - t0) / 580.7, "1/580 of the distance". Near
//   samples are dense where the screen footprint is small, far ones sparse.
//
// After the first sample with f >= 0, bisection refines the bracket [t_outside, t_inside]
// ("step back half a step, halve, step forward or back by the sign") until it is
// no wider than `tolerance`; the midpoint is returned, within tolerance / 2 of a simple root.
#pragma once
#include <limits>

#include "raster/march/ray_packet.h"

namespace tessera::march {

enum class StepStrategy { uniform, geometric };

struct MarchSettings {
    StepStrategy strategy = StepStrategy::uniform;
    int steps = 128;
    float max_step = std::numeric_limits<float>::infinity();  // uniform only
    float growth = 1.02f;                                      // geometric only
    bool refine = true;
    float tolerance = 1e-3f;  // world units; bisection stops at this bracket width

    // Throws std::invalid_argument naming the bad field: steps < 1 (or absurdly many), a
    // non-positive or NaN max_step or tolerance, a growth that is NaN or not above 1.
    void validate() const;

    // The first step and the per-step factor for `segment` (growth 1 for uniform).
    struct Schedule {
        float first_step;
        float growth;
    };
    Schedule schedule(Interval segment) const { return schedule(segment, steps_sum()); }
    // The same with steps_sum() given, so a packet computes it once for all its lanes.
    Schedule schedule(Interval segment, double steps_sum) const;
    // The sum of the geometric step factors, (g^n - 1) / (g - 1), in double (1 for uniform).
    double steps_sum() const;
};

}  // namespace tessera::march
