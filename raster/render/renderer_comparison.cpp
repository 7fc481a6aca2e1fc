#include "raster/render/renderer_comparison.h"

#include <stdexcept>

#include "raster/core/trace.h"
#include "raster/embree/shadow_rays.h"
#include "raster/render/frame_renderer.h"
#include "raster/shadow/light_mask.h"
#include "raster/shadow/shadow_map.h"

namespace tessera::render {

StillFrame still_frame(AnimatedScene& scene, float time, int width, int height) {
    StillFrame frame;
    scene.set_time(time, float(width) / float(height));
    frame.baked = scene::bake(scene.scene);
    embree::reserve_ray_padding(frame.baked.mesh);
    frame.camera = scene.scene.camera;
    frame.lights = scene.scene.lights;
    for (const scene::Light& light : frame.lights) frame.light_targets.push_back(shadow_target(light));
    return frame;
}

IdAgreement compare_triangle_ids(const VisibilityBuffer& a, const VisibilityBuffer& b) {
    if (a.width != b.width || a.height != b.height || a.triangle.size() != b.triangle.size())
        throw std::invalid_argument("compare_triangle_ids: the visibility buffers differ in size");
    IdAgreement agreement;
    agreement.pixels = a.triangle.size();
    for (size_t p = 0; p < a.triangle.size(); ++p) agreement.equal += a.triangle[p] == b.triangle[p];
    return agreement;
}

ShadowMethods compare_shadow_methods(pipeline::Rasterizer& rasterizer, const embree::RayScene& rays,
                                     const StillFrame& frame, const VisibilityBuffer& visibility) {
    if (frame.light_targets.empty()) throw std::invalid_argument("compare_shadow_methods: the frame has no lights");
    const Mesh& mesh = frame.baked.mesh;
    const glm::mat4 vp = frame.camera.view_projection();
    const std::vector<glm::vec3>& lights = frame.light_targets;
    ShadowMethods out;

    auto t0 = Clock::now();
    std::vector<shadow::ShadowMap> maps;
    build_shadow_maps(rasterizer, mesh, frame.lights, frame.camera, maps);
    const shadow::LightMask by_maps = shadow::compute_light_mask(visibility, mesh, vp, lights, shadow::shadow_map_test(maps));
    out.maps_ms = ms_since(t0);

    t0 = Clock::now();
    const shadow::LightMask by_rays = shadow::compute_light_mask(visibility, mesh, vp, lights, embree::shadow_ray_test(rays));
    out.rays_ms = ms_since(t0);

    const shadow::LightMask grazing =
        shadow::compute_light_mask(visibility, mesh, vp, lights, shadow::grazing_lights(kGrazingCosine));
    out.all = shadow::compare_light_masks(by_maps, by_rays, visibility);
    out.non_grazing = shadow::compare_light_masks(by_maps, by_rays, visibility, &grazing);
    return out;
}

BvhTimes time_bvh(const embree::RayDevice& device, const Mesh& mesh) {
    BvhTimes out;
    auto t0 = Clock::now();
    { const embree::RayScene built(device, mesh, embree::BvhUpdate::none); }
    out.build_ms = ms_since(t0);
    embree::RayScene dynamic(device, mesh, embree::BvhUpdate::refit);
    t0 = Clock::now();
    dynamic.update();
    out.refit_ms = ms_since(t0);
    return out;
}

}  // namespace tessera::render
