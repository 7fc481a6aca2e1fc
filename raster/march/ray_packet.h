// A packet of primary rays in structure-of-arrays form: one lane per pixel of a horizontal run
// of kMarchLanes pixels, the SIMD width of raster/simd (16 with AVX-512, 8 with AVX2, 1 in the
// scalar build), so a packet's lanes are one simd::vfloat.
#pragma once
#include <glm/glm.hpp>

#include "raster/simd/simd.h"

namespace tessera::march {

inline constexpr int kMarchLanes = simd::kLanes;

// Lanes beyond `count` are padding: they carry a valid ray (a copy of lane 0) so arithmetic on
// them is harmless, and every consumer ignores them.
struct RayPacket {
    alignas(64) float ox[kMarchLanes];
    alignas(64) float oy[kMarchLanes];
    alignas(64) float oz[kMarchLanes];
    alignas(64) float dx[kMarchLanes];  // unit directions
    alignas(64) float dy[kMarchLanes];
    alignas(64) float dz[kMarchLanes];
    int count = 0;  // live lanes, 1..kMarchLanes

    glm::vec3 origin(int lane) const { return {ox[lane], oy[lane], oz[lane]}; }
    glm::vec3 direction(int lane) const { return {dx[lane], dy[lane], dz[lane]}; }
    glm::vec3 at(int lane, float t) const { return origin(lane) + direction(lane) * t; }
};

// A parametric range [t0, t1] along a ray; empty when t0 > t1.
struct Interval {
    float t0 = 0.0f;
    float t1 = -1.0f;
    bool empty() const { return !(t0 <= t1); }
};

}  // namespace tessera::march
