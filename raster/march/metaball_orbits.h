// Animated metaball centres (at least 3 balls, animated centres):
// ball i moves on a Lissajous orbit around the origin with its own periods and phases, so
// the balls drift into and out of each other and the blend between them is visible.
#pragma once
#include <glm/glm.hpp>

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "raster/march/metaball_field.h"

namespace tessera::march {

// `count` balls of support radius `radius` at time `seconds`; deterministic in both.
inline std::vector<Metaball> orbiting_metaballs(int count, float seconds, float radius = 1.0f) {
    if (count < 0 || count > 4096)
        throw std::invalid_argument("metaballs: ball count must be in 0..4096, got " +
                                    std::to_string(count));
    std::vector<Metaball> balls;
    for (int i = 0; i < count; ++i) {
        const float k = float(i);
        // Angular speeds 0.7 .. 1.3 rad/s and phases spread by the golden angle keep the
        // orbits from synchronising.
        const float wx = 0.7f + 0.23f * std::fmod(k * 1.618034f, 2.6f);
        const float wy = 1.1f - 0.17f * std::fmod(k * 2.236068f, 2.3f);
        const float phase = k * 2.399963f;
        const glm::vec3 centre(0.9f * std::sin(wx * seconds + phase),
                               0.6f * std::sin(wy * seconds + 1.7f * phase),
                               0.9f * std::cos(0.8f * wx * seconds + phase));
        balls.push_back({centre, radius, 1.0f});
    }
    return balls;
}

}  // namespace tessera::march
