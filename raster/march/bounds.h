// Bounding volumes that give the marcher its [t0, t1] per ray, so no step is spent where the
// surface cannot be:
// - a slab between two horizontal planes (the terrain lies between y = 0 and
//   y = 1; "t1 = (1 - eye.y) / d.y, t2 = (0 - eye.y) / d.y, tstar = max(min(t1, t2), 0),
//   tend = max(max(t1, t2), 0)"), capped at a far distance because a ray parallel to the
//   planes and inside the slab never leaves it;
// - a sphere (metaball supports, the test sphere).
#pragma once
#include <glm/glm.hpp>

#include "raster/march/ray_packet.h"

namespace tessera::march {

struct Slab {
    float y_low = 0.0f;
    float y_high = 1.0f;

    // Throws std::invalid_argument unless y_low < y_high, both finite.
    void validate() const;

    // The part of the ray o + t d, t in [0, t_far], between the planes.
    Interval clip(glm::vec3 o, glm::vec3 d, float t_far) const;
};

// The part of the ray o + t d (|d| = 1), t in [0, t_far], inside the sphere (centre, radius).
Interval sphere_interval(glm::vec3 o, glm::vec3 d, glm::vec3 centre, float radius, float t_far);

}  // namespace tessera::march
