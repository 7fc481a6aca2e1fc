// Multisample positions: the standard patterns of Direct3D 11 (D3D11_STANDARD_MULTISAMPLE_
// PATTERN) which Vulkan adopts as its standard sample locations, in 1/16 pixel units relative
// to the pixel centre, y down. One sample is the pixel centre itself.
//
// The rasterizer (coverage and depth per sample), the reference rasterizer and the ray caster
// (one primary ray per sample) all read these positions, so raster and ray-cast frames stay
// comparable sample for sample.
#pragma once
#include <glm/glm.hpp>

#include <array>
#include <cstdint>
#include <span>
#include <stdexcept>
#include <string>

namespace tessera::pipeline {

struct SampleOffset {
    int8_t x, y;  // 1/16 pixel from the pixel centre, in [-8, 7]
};

inline constexpr int kMaxSamples = 16;

// The positions of a `samples`-sample pixel, in sample order. Throws std::invalid_argument
// unless samples is 1, 4, 8 or 16.
inline std::span<const SampleOffset> sample_pattern(int samples) {
    static constexpr SampleOffset one[] = {{0, 0}};
    static constexpr SampleOffset four[] = {{-2, -6}, {6, -2}, {-6, 2}, {2, 6}};
    static constexpr SampleOffset eight[] = {{1, -3}, {-1, 3}, {5, 1}, {-3, -5},
                                             {-5, 5}, {-7, -1}, {3, 7}, {7, -7}};
    static constexpr SampleOffset sixteen[] = {{1, 1},   {-1, -3}, {-3, 2}, {4, -1},  {-5, -2}, {2, 5},
                                               {5, 3},   {3, -5},  {-2, 6}, {0, -7},  {-4, -6}, {-6, 4},
                                               {-8, 0},  {7, -4},  {6, 7},  {-7, -8}};
    switch (samples) {
        case 1: return one;
        case 4: return four;
        case 8: return eight;
        case 16: return sixteen;
        default:
            throw std::invalid_argument("samples: " + std::to_string(samples) + " is not a sample count (expected 1, 4, 8 or 16)");
    }
}

// The same positions as offsets from the pixel centre in pixels (CoverageLayers::build).
inline const glm::vec2* sample_positions(int samples) {
    static const auto table = [] {
        std::array<std::array<glm::vec2, kMaxSamples>, kMaxSamples + 1> t{};
        for (int n : {1, 4, 8, 16}) {
            const auto pattern = sample_pattern(n);
            for (size_t s = 0; s < pattern.size(); ++s)
                t[size_t(n)][s] = glm::vec2(float(pattern[s].x), float(pattern[s].y)) * (1.0f / 16.0f);
        }
        return t;
    }();
    sample_pattern(samples);  // throws for a bad count
    return table[size_t(samples)].data();
}

inline bool valid_sample_count(int samples) { return samples == 1 || samples == 4 || samples == 8 || samples == 16; }

}  // namespace tessera::pipeline
