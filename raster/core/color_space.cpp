#include "raster/core/color_space.h"

#include <cmath>

namespace tessera {
namespace {

float clamp01(float x) { return x > 0.0f ? (x < 1.0f ? x : 1.0f) : 0.0f; }  // NaN -> 0

}  // namespace

float linear_to_srgb(float linear) {
    const float c = clamp01(linear);
    if (c >= 1.0f) return 1.0f;  // exact, where 1.055 - 0.055 rounds to 1 - 2^-24
    return c <= 0.0031308f ? 12.92f * c : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
}

float srgb_to_linear(float encoded) {
    const float e = clamp01(encoded);
    return e <= 0.04045f ? e / 12.92f : std::pow((e + 0.055f) / 1.055f, 2.4f);
}

}  // namespace tessera
