// The ray-cast renderer's visibility pass: one primary ray per pixel centre, traced by Embree,
// written into the same VisibilityBuffer the rasterizer fills (triangle id = the mesh's id of
// the hit, RayScene::triangle; window depth = the hit triangle's plane through the same
// view-projection, evaluated at the pixel centre, i.e. the exact depth of the hit, see
// PixelRays::depth_plane), so shading cannot tell which renderer found the surface.
//
// Work is split into fixed 32x32-pixel tiles run in parallel by oneTBB; inside a tile, rays go
// in coherent packets (4x2 pixels for 8 lanes, 4x4 for 16) or one at a time (the reference
// path). Every pixel is computed independently, so the output is identical for any thread
// count and any packet width.
#pragma once
#include <glm/glm.hpp>

#include <cstdint>
#include <span>

#include "raster/embree/scene.h"
#include "raster/core/visibility.h"

namespace tessera::embree {

// How rays are handed to Embree: one at a time (rtcIntersect1 / rtcOccluded1) or as coherent
// packets of 8 or 16 (rtcIntersect8/16, rtcOccluded8/16 with the COHERENT context flag).
enum class RayPacket { single = 1, x8 = 8, x16 = 16 };

// Resets `out` to width x height and fills it. Rays pass through the triangles t with
// skip[t] != 0 (transparent ones, blended afterwards as the rasterizer does: its opaque pass
// leaves them out too); `skip` is empty or has one entry per triangle. Throws
// std::invalid_argument for a non-positive size, a `skip` of the wrong length or a bad
// sample count.
//
// samples > 1: one ray per sample position of sample_pattern.h (the rasterizer's), depth
// from the hit triangle's plane at the sample, into out's per-sample arrays, and each
// pixel's main surface into triangle and depth, as the rasterizer's multisampled renders.
void cast_primary_rays(const RayScene& scene, const glm::mat4& view_projection, int width,
                       int height, VisibilityBuffer& out, RayPacket packet = RayPacket::x16,
                       std::span<const uint8_t> skip = {}, int samples = 1);

}  // namespace tessera::embree
