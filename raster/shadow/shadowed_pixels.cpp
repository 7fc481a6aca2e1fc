#include "raster/shadow/shadowed_pixels.h"

#include <cmath>
#include <stdexcept>

#include "raster/core/color_space.h"

namespace tessera::shadow {
namespace {

float level(float linear) { return std::floor(linear_to_srgb(linear) * 255.0f + 0.5f); }

float luma(const glm::vec4& c) {
    return 0.2126f * level(c.r) + 0.7152f * level(c.g) + 0.0722f * level(c.b);
}

void check_size(const Frame& a, const Frame& b) {
    if (a.width != b.width || a.height != b.height || a.pixels.size() != b.pixels.size())
        throw std::invalid_argument("frames to compare shadows on differ in size");
}

}  // namespace

std::vector<uint8_t> shadowed_pixels(const Frame& unshadowed, const Frame& shadowed, float levels) {
    check_size(unshadowed, shadowed);
    std::vector<uint8_t> mask(shadowed.pixels.size());
    for (size_t p = 0; p < mask.size(); ++p)
        mask[p] = luma(unshadowed.pixels[p]) - luma(shadowed.pixels[p]) > levels;
    return mask;
}

ShadowDisagreement compare_shadowed_pixels(const Frame& unshadowed, const Frame& a, const Frame& b,
                                           float levels) {
    check_size(unshadowed, b);
    const std::vector<uint8_t> by_a = shadowed_pixels(unshadowed, a, levels);
    const std::vector<uint8_t> by_b = shadowed_pixels(unshadowed, b, levels);
    ShadowDisagreement d;
    for (size_t p = 0; p < by_a.size(); ++p) {
        d.shadowed_a += by_a[p];
        d.shadowed_b += by_b[p];
        d.either += by_a[p] | by_b[p];
        d.differ += by_a[p] ^ by_b[p];
    }
    return d;
}

}  // namespace tessera::shadow
