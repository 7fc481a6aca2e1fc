// `tessera shadows`: the shadow comparison on the sphere-grid scene. The rasterizer finds the
// visible surface once; then shadows are decided two ways, by shadow maps rendered with the
// rasterizer from each light and by Embree shadow rays, and the two light masks are compared
// (agreement over all covered pixels and over non-grazing ones) and written as a diff image.
// It also ray-casts the same frame and counts pixels whose triangle id differs from the
// rasterizer's (exact-edge ties).
#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

#include "examples/command.h"
#include "raster/core/atomic_file.h"
#include "raster/embree/ray_cast.h"
#include "raster/embree/scene.h"
#include "raster/embree/shadow_rays.h"
#include "raster/io/image_io.h"
#include "raster/pipeline/rasterizer.h"
#include "raster/shadow/mask_compare.h"
#include "raster/shadow/shadow_map.h"
#include "raster/workloads/sphere_grid.h"

namespace tessera::cli {
namespace {

struct Options {
    size_t triangles = 100000;
    std::string size = "1920x1080";
    int lights = 1;
    shadow::ShadowMapOptions map;
    float grazing = 0.1f;
    std::string diff;
    int threads = 0;
};

double milliseconds_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
        .count();
}

std::vector<glm::vec3> scene_lights(const workloads::SphereGridScene& grid, int count) {
    const float e = float(grid.grid);
    const std::vector<glm::vec3> all = {grid.light, {-0.7f * e, 1.2f * e, 0.4f * e},
                                        {0.2f * e, 1.8f * e, -0.8f * e},
                                        {-0.3f * e, 1.0f * e, 1.0f * e}};
    return {all.begin(), all.begin() + count};
}

int run(const Options& o) {
    int width = 0, height = 0;
    parse_size(o.size, "--size", width, height);
    if (!o.diff.empty()) {  // checked before the work, not after it
        if (!io::image_format_supported(o.diff)) throw UsageError("--diff: no image writer for '" + o.diff + "'");
        check_writable(o.diff);
    }
    const auto cap = limit_threads(o.threads);
    using clock = std::chrono::steady_clock;

    workloads::SphereGridScene grid = workloads::make_sphere_grid(o.triangles, float(width) / float(height));
    const glm::mat4 vp = grid.camera.view_projection();
    const std::vector<glm::vec3> lights = scene_lights(grid, o.lights);

    pipeline::Rasterizer rasterizer;
    VisibilityBuffer raster_vis;
    auto start = clock::now();
    rasterizer.render(grid.mesh, vp, pipeline::Viewport(width, height), pipeline::RasterOptions{}, raster_vis);
    const double raster_ms = milliseconds_since(start);

    start = clock::now();
    const embree::RayScene scene(embree::default_ray_device(), grid.mesh);
    const double build_ms = milliseconds_since(start);
    VisibilityBuffer ray_vis;
    start = clock::now();
    embree::cast_primary_rays(scene, vp, width, height, ray_vis);
    const double cast_ms = milliseconds_since(start);
    size_t id_differ = 0;
    for (size_t p = 0; p < raster_vis.triangle.size(); ++p)
        id_differ += raster_vis.triangle[p] != ray_vis.triangle[p];

    start = clock::now();
    std::vector<shadow::ShadowMap> maps;
    for (const glm::vec3& light : lights) maps.emplace_back(rasterizer, grid.mesh, light, o.map);
    const shadow::LightMask by_map = shadow::compute_light_mask(
        raster_vis, grid.mesh, vp, lights, shadow::shadow_map_test(maps));
    const double map_ms = milliseconds_since(start);
    start = clock::now();
    const shadow::LightMask by_rays =
        shadow::compute_light_mask(raster_vis, grid.mesh, vp, lights, embree::shadow_ray_test(scene));
    const double rays_ms = milliseconds_since(start);
    const shadow::LightMask grazing = shadow::compute_light_mask(
        raster_vis, grid.mesh, vp, lights, shadow::grazing_lights(o.grazing));

    const auto all = shadow::compare_light_masks(by_map, by_rays, raster_vis);
    const auto steep = shadow::compare_light_masks(by_map, by_rays, raster_vis, &grazing);
    std::printf("scene: %zu triangles, %dx%d, %d light(s), shadow map %d^2, PCF %dx%d\n",
                grid.mesh.triangle_count(), width, height, o.lights, o.map.resolution,
                2 * o.map.pcf_radius + 1, 2 * o.map.pcf_radius + 1);
    std::printf("visibility: raster %.2f ms, embree %.2f ms (+ BVH build %.2f ms); "
                "triangle ids differ at %zu of %zu pixels\n",
                raster_ms, cast_ms, build_ms, id_differ, raster_vis.triangle.size());
    std::printf("shadows: maps + lookups %.2f ms, embree rays %.2f ms (%.0f%%; one cold run, "
                "bench_raytrace measures)\n", map_ms,
                rays_ms, 100.0 * map_ms / rays_ms);
    std::printf("agreement: %.4f%% of %zu covered pixels; %.4f%% of %zu non-grazing "
                "(cos < %.2f left out: %zu); map-only lit %zu, rays-only lit %zu\n",
                100.0 * all.agreement(), all.compared, 100.0 * steep.agreement(), steep.compared,
                o.grazing, steep.excluded, steep.only_a_lit, steep.only_b_lit);
    if (!o.diff.empty()) {
        shadow::write_mask_diff(o.diff, by_map, by_rays, raster_vis, &grazing);
        std::printf("diff: %s (red: lit only by the map, blue: only by rays, olive: grazing)\n",
                    o.diff.c_str());
    }
    return 0;
}

Run define_shadows(CLI::App& root) {
    auto options = std::make_shared<Options>();
    CLI::App* command = root.add_subcommand(
        "shadows", "compare shadow maps with Embree shadow rays on the sphere-grid scene");
    command->add_option("--triangles", options->triangles, "scene size")
        ->check(CLI::Range(size_t(24), size_t(16'000'000)))
        ->capture_default_str();
    command->add_option("--size", options->size, "image WxH")->capture_default_str();
    command->add_option("--lights", options->lights, "point lights")
        ->check(CLI::Range(1, 4))
        ->capture_default_str();
    command->add_option("--map-size", options->map.resolution, "shadow map resolution")
        ->check(CLI::Range(16, 8192))
        ->capture_default_str();
    command->add_option("--pcf", options->map.pcf_radius, "PCF radius (taps: (2r+1)^2)")
        ->check(CLI::Range(0, 8))
        ->capture_default_str();
    command->add_option("--normal-offset", options->map.normal_offset, "bias along the normal, texels")
        ->check(CLI::Range(0.0f, 64.0f))
        ->capture_default_str();
    command->add_option("--depth-bias", options->map.depth_bias, "bias towards the light, texels")
        ->check(CLI::Range(0.0f, 64.0f))
        ->capture_default_str();
    command->add_option("--grazing", options->grazing,
                        "leave out lights with cos(normal, light) below this")
        ->check(CLI::Range(0.0f, 1.0f))
        ->capture_default_str();
    command->add_option("--diff", options->diff, "write the diff image here (.png, .exr, ...)");
    add_threads_option(*command, options->threads);
    return [options] { return run(*options); };
}

TESSERA_COMMAND(60, define_shadows);

}  // namespace
}  // namespace tessera::cli
