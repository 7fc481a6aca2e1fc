// Directions given as vectors of any length: a rotation axis, a light direction, a camera's
// up. Normalising squares the components, so [3e38, 3e38, 3e38] overflows to Inf (the object
// vanishes, the light goes black) and [1e-30, 1e-30, 1e-30] underflows to 0. Such a vector is
// divided by its largest component first, which keeps its direction: [3e38, 3e38, 3e38] and
// [1e-30, 1e-30, 1e-30] both become [1, 1, 1], and then render exactly as [1, 1, 1] does. A
// vector whose squared length is an ordinary float is left as it is, so every direction that
// normalised well before gives the same bits as before.
#pragma once
#include <glm/glm.hpp>

#include <cfloat>
#include <cmath>
#include <optional>

namespace tessera {

// `v`, or `v` divided by its largest component when its squared length would overflow or
// lose precision (below FLT_MIN); nullopt when `v` is zero or has a NaN or infinite component.
template <glm::length_t N>
std::optional<glm::vec<N, float>> normalisable(glm::vec<N, float> v) {
    float largest = 0.0f;
    for (glm::length_t i = 0; i < N; ++i) {
        if (!std::isfinite(v[i])) return std::nullopt;
        largest = std::fmax(largest, std::fabs(v[i]));
    }
    if (!(largest > 0.0f)) return std::nullopt;
    const float squared = glm::dot(v, v);
    if (std::isfinite(squared) && squared >= FLT_MIN) return v;
    return v / largest;
}

// The unit vector along `v` (glm::normalize, after normalisable()); nullopt as there.
template <glm::length_t N>
std::optional<glm::vec<N, float>> unit_direction(glm::vec<N, float> v) {
    const auto scaled = normalisable(v);
    if (!scaled) return std::nullopt;
    return glm::normalize(*scaled);
}

}  // namespace tessera
