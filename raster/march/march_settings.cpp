#include "raster/march/march_settings.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace tessera::march {

namespace {
// 2^16 steps per ray is already far beyond any image-quality gain; more is a typo.
constexpr int kMaxSteps = 1 << 16;
}  // namespace

void MarchSettings::validate() const {
    if (steps < 1 || steps > kMaxSteps)
        throw std::invalid_argument("ray march: steps must be in 1.." + std::to_string(kMaxSteps) +
                                    ", got " + std::to_string(steps));
    if (!(max_step > 0.0f))
        throw std::invalid_argument("ray march: max_step must be positive, got " +
                                    std::to_string(max_step));
    if (!(growth > 1.0f) || !std::isfinite(growth))
        throw std::invalid_argument("ray march: geometric growth must be a finite factor above 1, got " +
                                    std::to_string(growth));
    if (!(tolerance > 0.0f) || !std::isfinite(tolerance))
        throw std::invalid_argument("ray march: refinement tolerance must be positive and finite, got " +
                                    std::to_string(tolerance));
}

double MarchSettings::steps_sum() const {
    if (strategy == StepStrategy::uniform) return 1.0;
    const double g = growth;
    return (std::pow(g, double(steps)) - 1.0) / (g - 1.0);
}

MarchSettings::Schedule MarchSettings::schedule(Interval segment, double steps_sum) const {
    const float length = segment.t1 - segment.t0;
    if (strategy == StepStrategy::uniform)
        return {std::min(length / float(steps), max_step), 1.0f};
    // Sum of the geometric series dt0 (g^n - 1) / (g - 1) = length, computed in double so the
    // last step lands on t1 to float precision.
    return {float(double(length) / steps_sum), growth};
}

}  // namespace tessera::march
