// A sphere written as an implicit field, f(p) = R - |p - c| (positive inside): the surface
// whose exact ray intersection is known in closed form, so it calibrates the marcher (tests)
// and gives the cheapest field for measuring the marching loop itself (bench).
#pragma once
#include <glm/glm.hpp>

#include <cmath>

#include "raster/march/ray_packet.h"

namespace tessera::march {

struct SphereField {
    glm::vec3 centre{0.0f};
    float radius = 1.0f;

    float value(glm::vec3 p) const { return radius - glm::length(p - centre); }

    // -(p - c) / |p - c|; zero at the centre, where the direction is undefined.
    glm::vec3 gradient(glm::vec3 p) const {
        const glm::vec3 q = p - centre;
        const float len = glm::length(q);
        return len > 0.0f ? -q / len : glm::vec3(0.0f);
    }

    void values(const float* x, const float* y, const float* z, float* out) const {
        for (int i = 0; i < kMarchLanes; ++i) {
            const float qx = x[i] - centre.x, qy = y[i] - centre.y, qz = z[i] - centre.z;
            out[i] = radius - std::sqrt(qx * qx + qy * qy + qz * qz);
        }
    }
};

}  // namespace tessera::march
