// The measurements behind `tessera compare` that the frame renderer does not report itself:
// one still frame's geometry put through each renderer's pieces side by side, one run each
// (the caller repeats and takes medians).
// - visibility agreement: the rasterizer's and Embree's triangle ids, pixel for pixel (they
//   differ only where an edge passes exactly through a pixel centre and a tie is broken
//   differently, or where the fixed-point snap moves an edge past a centre);
// - shadows: shadow maps (rendered by the rasterizer from each light with its own settings,
//   cascades fitted to the camera, as the frame renderer renders them, then looked up) against
//   Embree shadow rays, both over the same visible points, timed and compared as light masks
//   (shadow/mask_compare.h), overall and away from grazing light;
// - the BVH: a full build (the static quality a still frame uses) against a refit (what an
//   animation of the same topology pays per frame).
#pragma once
#include <glm/glm.hpp>

#include <vector>

#include "raster/core/camera.h"
#include "raster/core/visibility.h"
#include "raster/embree/device.h"
#include "raster/embree/scene.h"
#include "raster/pipeline/rasterizer.h"
#include "raster/render/animated_scene.h"
#include "raster/scene/scene.h"
#include "raster/shadow/mask_compare.h"

namespace tessera::render {

// The scene at one time as one world-space mesh, its camera, its lights and the points they
// shine from (as the frame renderer aims shadow rays: shadow_target()).
struct StillFrame {
    scene::BakedScene baked;
    Camera camera;
    std::vector<scene::Light> lights;
    std::vector<glm::vec3> light_targets;
};
StillFrame still_frame(AnimatedScene& scene, float time, int width, int height);

struct IdAgreement {
    size_t pixels = 0;
    size_t equal = 0;  // pixels where both found the same triangle (or both none)
    double fraction() const { return pixels ? double(equal) / double(pixels) : 1.0; }
};
// Throws std::invalid_argument when the buffers' sizes differ.
IdAgreement compare_triangle_ids(const VisibilityBuffer& a, const VisibilityBuffer& b);

struct ShadowMethods {
    double maps_ms = 0;  // every light's shadow maps rendered, then every visible point looked up
    double rays_ms = 0;  // an Embree occlusion ray from every visible point to every light
    shadow::MaskAgreement all;          // over every covered pixel
    shadow::MaskAgreement non_grazing;  // leaving out points a light meets at cos < kGrazingCosine
};
inline constexpr float kGrazingCosine = 0.1f;

// Both shadow methods over the points `visibility` shows (found by either renderer on
// frame.baked.mesh). `rays` is a BVH over that mesh. Needs at least one light.
ShadowMethods compare_shadow_methods(pipeline::Rasterizer& rasterizer, const embree::RayScene& rays,
                                     const StillFrame& frame, const VisibilityBuffer& visibility);

struct BvhTimes {
    double build_ms = 0;  // a static BVH (BvhUpdate::none, Embree's MEDIUM quality)
    double refit_ms = 0;  // RayScene::update() of a refittable BVH (BvhUpdate::refit)
};
BvhTimes time_bvh(const embree::RayDevice& device, const Mesh& mesh);

}  // namespace tessera::render
