#include "raster/march/bounds.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace tessera::march {

void Slab::validate() const {
    if (!std::isfinite(y_low) || !std::isfinite(y_high) || !(y_low < y_high))
        throw std::invalid_argument("ray march: bounding slab needs finite y_low < y_high, got " +
                                    std::to_string(y_low) + " .. " + std::to_string(y_high));
}

Interval Slab::clip(glm::vec3 o, glm::vec3 d, float t_far) const {
    if (d.y == 0.0f) {  // parallel to the planes: inside everywhere or nowhere
        if (o.y < y_low || o.y > y_high) return {};
        return {0.0f, t_far};
    }
    const float ta = (y_high - o.y) / d.y;
    const float tb = (y_low - o.y) / d.y;
    return {std::max(std::min(ta, tb), 0.0f), std::min(std::max(ta, tb), t_far)};
}

Interval sphere_interval(glm::vec3 o, glm::vec3 d, glm::vec3 centre, float radius, float t_far) {
    // |o + t d - c|^2 = r^2 with |d| = 1: t^2 + 2 b t + c = 0, b = d.(o - c).
    const glm::vec3 oc = o - centre;
    const float b = glm::dot(d, oc);
    // The discriminant in the form r^2 - |oc - b d|^2 avoids the cancellation of b^2 - |oc|^2
    // + r^2 when the sphere is far away.
    const glm::vec3 perpendicular = oc - b * d;
    const float disc = radius * radius - glm::dot(perpendicular, perpendicular);
    if (disc < 0.0f) return {};
    const float root = std::sqrt(disc);
    return {std::max(-b - root, 0.0f), std::min(-b + root, t_far)};
}

}  // namespace tessera::march
