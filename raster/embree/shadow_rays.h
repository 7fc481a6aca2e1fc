// Hard shadows by Embree occlusion rays: from each visible surface point to each point light.
//
// A ray starts at the point pushed off the surface along its normal by
// kShadowRayOffset * (1 + max|p|) (a relative epsilon: float positions carry relative error,
// research note 3.2 item 4) and ends exactly at the light (t in [0, 1]). Points whose surface
// faces away from a light are not traced: the light cannot reach them.
//
// Rays go in coherent packets of 8 or 16 consecutive points facing the light (the tile's 4x4
// pixel blocks, see surface_points.h, less the points facing away, so every lane of a packet
// is a ray; the facing test and the rays set up in lanes, see shadow_rays.cpp) through
// rtcOccluded8/16 with the COHERENT flag, or one at a time through rtcOccluded1 (the
// reference path). Both give the same answer ray for ray.
#pragma once
#include <glm/glm.hpp>

#include <cstdint>
#include <span>

#include "raster/embree/ray_cast.h"
#include "raster/embree/scene.h"
#include "raster/shadow/light_mask.h"
#include "raster/shadow/surface_points.h"

namespace tessera::embree {

inline constexpr float kShadowRayOffset = 1.0f / 65536.0f;

// Sets visible[i] bit l when lights[l] reaches points[i] (a shadow::LightTest).
void trace_shadow_rays(const RayScene& scene, const shadow::SurfacePoints& points,
                       std::span<const glm::vec3> lights, std::span<uint8_t> visible,
                       RayPacket packet = RayPacket::x16);

// trace_shadow_rays bound to a scene and packet width, for shadow::compute_light_mask.
shadow::LightTest shadow_ray_test(const RayScene& scene, RayPacket packet = RayPacket::x16);

}  // namespace tessera::embree
