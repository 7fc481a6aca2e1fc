// Where two cost curves cross: given both renderers' times at increasing triangle counts
// (`tessera compare --sweep`), the triangle count at which the faster one changes.
//
// Costs grow roughly as powers of the triangle count (the rasterizer linearly, ray casting
// logarithmically per ray plus a linear BVH build), so the crossing is found on log-log axes:
// the sign change of log(b / a) between two neighbouring samples, interpolated linearly in
// log(triangles). That is exact for power laws and is what the plot, drawn with log axes,
// shows.
#pragma once
#include <optional>
#include <span>

namespace tessera::render {

struct CostSample {
    double triangles = 0;
    double a_ms = 0;  // e.g. the rasterizer
    double b_ms = 0;  // e.g. the ray caster
};

struct Crossover {
    double triangles = 0;  // where a and b cost the same
    // True when b is the faster one beyond the crossing (above `triangles`), false when a is.
    bool b_faster_above = false;
};

// The first crossing over `samples` in increasing triangle count. Samples with a non-positive
// count or time, or not above the previous one's count, are skipped; a sample where both cost
// exactly the same is the crossing if the faster side differs before and after it. None when
// one side is never slower.
std::optional<Crossover> find_crossover(std::span<const CostSample> samples);

}  // namespace tessera::render
