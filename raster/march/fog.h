// Participating medium along the eye ray: radiance changes by absorption /
// out-scattering and in-scattering, dL/ds = -sigma(s) L + sigma(s) C, whose solution from the
// surface at distance D to the eye is
//     L_eye = T L_surface + (1 - T) C,   T = exp(-tau),   tau = int_0^D sigma(o + t d) dt.
// C is the fog's colour (the source term divided by its attenuation); C = 0 is the
// "black fog". sigma and C are RGB, so the fog can be coloured.
//
// Density: sigma(p) = density * exp(-falloff (p.y - base_height)): falloff 0 is the constant
// fog, falloff > 0 a "denser low, thinner high" exponential height fog. Along
// y(t) = o_y + t d_y the integral has the closed form
//     tau = density e^{-b (o_y - y0)} D (1 - e^{-x}) / x,   x = b d_y D,
// and (1 - e^{-x}) / x -> 1 for a horizontal ray (x -> 0), where the division is replaced by
// its series 1 - x/2 + x^2/6 for |x| < 1e-4 (relative error below x^3/24 ~ 4e-14).
// The background is infinitely far: D = infinity gives tau = infinity (T = 0, pure fog
// colour) except for a height fog seen upward, which integrates to e^{-b (o_y - y0)} / (b d_y).
//
// The exponentials are simd::exp_of / expm1_of (double precision rounded once: the correctly
// rounded float but for near-ties), so the lane form of the transmittance, what the fog pass
// runs, gives exactly what the one-ray form gives at every lane width.
#pragma once
#include <glm/glm.hpp>

#include "raster/simd/lane_math.h"

namespace tessera::march {

struct Fog {
    glm::vec3 density{0.0f};  // extinction per unit length at base_height, per channel, >= 0
    glm::vec3 colour{0.0f};   // C
    float falloff = 0.0f;     // b >= 0, per unit height
    float base_height = 0.0f;  // y0

    // Throws std::invalid_argument for a negative or non-finite density or falloff, or a
    // non-finite colour or base height.
    void validate() const;

    bool enabled() const { return density.x > 0.0f || density.y > 0.0f || density.z > 0.0f; }

    // int_0^D e^{-b (y(t) - y0)} dt for the unit-direction ray from `origin` with
    // d_y = `direction_y`; `distance` may be infinity.
    float unit_optical_depth(float origin_y, float direction_y, float distance) const;

    // exp(-tau) per channel.
    glm::vec3 transmittance(glm::vec3 origin, glm::vec3 direction, float distance) const;
    // The same for kLanes rays from `origin`, given their directions' y and distances, one per
    // lane: equal lane by lane to the form above.
    simd::V3<simd::vfloat> transmittance(glm::vec3 origin, simd::vfloat direction_y, simd::vfloat distance) const;

    // What the eye sees of `radiance` leaving a surface `distance` away (infinity: background).
    glm::vec3 apply(glm::vec3 radiance, glm::vec3 origin, glm::vec3 direction, float distance) const {
        const glm::vec3 t = transmittance(origin, direction, distance);
        return t * radiance + (1.0f - t) * colour;
    }
};

}  // namespace tessera::march
