#include "raster/render/crossover.h"

#include <cmath>

namespace tessera::render {

std::optional<Crossover> find_crossover(std::span<const CostSample> samples) {
    // log(b / a): negative where b is faster.
    const auto lead = [](const CostSample& s) { return std::log(s.b_ms / s.a_ms); };
    const CostSample* side = nullptr;  // the last sample where one side was strictly faster
    double last_triangles = 0.0;
    double touch = 0.0;  // the first sample since `side` where both cost the same, or 0
    for (const CostSample& s : samples) {
        if (!(s.triangles > 0 && s.a_ms > 0 && s.b_ms > 0) || !(s.triangles > last_triangles)) continue;
        last_triangles = s.triangles;
        const double d = lead(s);
        if (d == 0.0) {
            if (touch == 0.0) touch = s.triangles;
            continue;
        }
        if (side && (lead(*side) < 0.0) != (d < 0.0)) {
            if (touch > 0.0) return Crossover{touch, d < 0.0};  // met exactly at a sample
            const double d0 = lead(*side);
            const double t = d0 / (d0 - d);
            const double x0 = std::log(side->triangles), x1 = std::log(s.triangles);
            return Crossover{std::exp(x0 + t * (x1 - x0)), d < 0.0};
        }
        side = &s;
        touch = 0.0;
    }
    return std::nullopt;
}

}  // namespace tessera::render
