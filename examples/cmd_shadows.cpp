// `tessera shadows`: shadow maps compared with Embree shadow rays.
//
// On the sphere-grid scene (the default): the rasterizer finds the visible surface once;
// then shadows are decided two ways, by shadow maps rendered with the rasterizer from each
// light and by Embree shadow rays, and the two light masks are compared (agreement over all
// covered pixels and over non-grazing ones) and written as a diff image. It also ray-casts
// the same frame and counts pixels whose triangle id differs from the rasterizer's
// (exact-edge ties).
//
// With --scene: one frame of a scene is rendered without shadows, with shadow maps and with
// shadow rays, --repeat times each, interleaved; the frames are compared as a viewer sees
// them (shadow/shadowed_pixels.h: shadowed where more than 8 luma levels darker than the
// unshadowed frame), and each method's wall and CPU time per frame (median) is printed.
#include <sys/resource.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "examples/command.h"
#include "examples/shadow_map_flags.h"
#include "raster/core/atomic_file.h"
#include "raster/output/frame_encoding.h"
#include "raster/render/frame_renderer.h"
#include "raster/scene_file/scene_build.h"
#include "raster/scene_file/scene_library.h"
#include "raster/scene_file/scene_parse.h"
#include "raster/shadow/shadowed_pixels.h"
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
    bool size_given = false;
    int lights = 1;
    ShadowMapFlags map_flags;
    float grazing = 0.1f;
    std::string diff;
    int threads = 0;
    // --scene
    std::string scene;
    int frame = -1;  // -1: the scene's first frame
    int repeat = 1;
    float levels = 8.0f;
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

// CPU time (user + system) of the whole process so far, every thread included.
double cpu_ms() {
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    const auto ms = [](const timeval& t) { return double(t.tv_sec) * 1e3 + double(t.tv_usec) * 1e-3; };
    return ms(usage.ru_utime) + ms(usage.ru_stime);
}

int run_scene(const Options& o) {
    const auto cap = limit_threads(o.threads);
    std::error_code ec;
    const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
    const std::filesystem::path file = scene_file::find_scene(
        o.scene, scene_file::scene_directories(TESSERA_SCENE_DIR, ec ? std::string() : exe.string()));
    std::vector<std::string> warnings;
    const scene_file::SceneSpec spec = scene_file::load_scene_file(file, warnings);
    for (const std::string& w : warnings) std::fprintf(stderr, "tessera: warning: %s\n", w.c_str());
    int width = spec.size.x, height = spec.size.y;
    if (o.size_given) parse_size(o.size, "--size", width, height);
    if (render::needs_bands(width, height))
        throw UsageError("--size: a frame this large is rendered in bands; compare a smaller one");
    const int frame = o.frame >= 0 ? o.frame : spec.animation.first;
    const float time = float(frame) / spec.animation.fps;
    render::AnimatedScene scene = scene_file::build_scene(spec, &warnings);
    o.map_flags.apply(scene.scene.lights);

    const render::ShadowMode modes[3] = {render::ShadowMode::none, render::ShadowMode::map, render::ShadowMode::rays};
    const char* names[3] = {"none", "map", "rays"};
    std::vector<std::unique_ptr<render::FrameRenderer>> renderers;
    for (const render::ShadowMode mode : modes)
        renderers.push_back(std::make_unique<render::FrameRenderer>(scene, width, height,
                                                                    render::RendererKind::raster, mode));
    Frame frames[3];
    std::vector<double> wall[3], cpu[3];
    for (int r = 0; r < o.repeat; ++r)
        for (int m = 0; m < 3; ++m) {
            const double cpu0 = cpu_ms();
            const auto t0 = std::chrono::steady_clock::now();
            renderers[size_t(m)]->render(time, frames[m]);
            wall[m].push_back(milliseconds_since(t0));
            cpu[m].push_back(cpu_ms() - cpu0);
        }
    const shadow::ShadowDisagreement d = shadow::compare_shadowed_pixels(frames[0], frames[1], frames[2], o.levels);
    std::printf("scene: %s frame %d (t = %.3f s), %dx%d, %zu light(s)\n", file.stem().c_str(), frame, double(time),
                width, height, scene.scene.lights.size());
    for (size_t l = 0; l < scene.scene.lights.size(); ++l) {
        const ShadowMapSettings& s = scene.scene.lights[l].shadow_map;
        std::printf("light %zu: shadow maps %d x %d^2, split blend %.2f, PCF %dx%d box, normal offset %.2f, "
                    "depth bias %.2f texels\n",
                    l, s.cascades, s.resolution, double(s.split_blend), 2 * s.pcf_radius + 1, 2 * s.pcf_radius + 1,
                    double(s.normal_offset), double(s.depth_bias));
    }
    std::printf("shadowed (luma more than %.0f levels below --shadows none): map %zu, rays %zu, either %zu\n",
                double(o.levels), d.shadowed_a, d.shadowed_b, d.either);
    std::printf("disagreement: %.2f%% (%zu of %zu pixels shadowed by only one method)\n", 100.0 * d.fraction(),
                d.differ, d.either);
    for (int m = 0; m < 3; ++m)
        std::printf("time %s: wall %.1f ms, cpu %.1f ms per frame (median of %d, interleaved)\n", names[m],
                    median(wall[m]), median(cpu[m]), o.repeat);
    if (!o.diff.empty()) {
        // White: shadowed by both; red: by the maps only; blue: by the rays only.
        const std::vector<uint8_t> by_map = shadow::shadowed_pixels(frames[0], frames[1], o.levels);
        const std::vector<uint8_t> by_rays = shadow::shadowed_pixels(frames[0], frames[2], o.levels);
        Frame diff(width, height, glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
        for (size_t p = 0; p < diff.pixels.size(); ++p)
            if (by_map[p] || by_rays[p])
                diff.pixels[p] = glm::vec4(by_map[p] ? 1.0f : 0.0f, by_map[p] && by_rays[p] ? 1.0f : 0.0f,
                                           by_rays[p] ? 1.0f : 0.0f, 1.0f);
        output::write_frame(o.diff, diff);
        std::printf("diff: %s (white: both shadow, red: only the maps, blue: only the rays)\n", o.diff.c_str());
    }
    return 0;
}

int run(const Options& o) {
    if (!o.diff.empty()) {  // checked before the work, not after it
        if (!output::frame_format_supported(o.diff)) throw UsageError("--diff: no image writer for '" + o.diff + "'");
        check_writable(o.diff);
    }
    if (!o.scene.empty()) return run_scene(o);
    if (o.frame >= 0 || o.repeat != 1) throw UsageError("--frame and --repeat go with --scene");
    int width = 0, height = 0;
    parse_size(o.size, "--size", width, height);
    const auto cap = limit_threads(o.threads);
    using clock = std::chrono::steady_clock;

    workloads::SphereGridScene grid = workloads::make_sphere_grid(o.triangles, float(width) / float(height));
    const glm::mat4 vp = grid.camera.view_projection();
    const std::vector<glm::vec3> lights = scene_lights(grid, o.lights);
    shadow::ShadowMapOptions map_options;
    map_options.cascades = 1;  // no camera fit here: one map over the grid
    o.map_flags.apply(map_options);

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
    for (const glm::vec3& light : lights) maps.emplace_back(rasterizer, grid.mesh, light, map_options);
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
                grid.mesh.triangle_count(), width, height, o.lights, map_options.resolution,
                2 * map_options.pcf_radius + 1, 2 * map_options.pcf_radius + 1);
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
        "shadows", "compare shadow maps with Embree shadow rays (the sphere grid, or a scene's frame)");
    command->add_option("--triangles", options->triangles, "scene size")
        ->check(CLI::Range(size_t(24), size_t(16'000'000)))
        ->capture_default_str();
    command->add_option("--size", options->size, "image WxH (with --scene, default: the scene's)")
        ->capture_default_str()
        ->each([options](const std::string&) { options->size_given = true; });
    command->add_option("--scene", options->scene,
                        "compare rendered frames of this scene (name or FILE.json) instead of the sphere grid");
    command->add_option("--frame", options->frame, "with --scene: the frame (default: the scene's first)")
        ->check(CLI::NonNegativeNumber);
    command->add_option("--repeat", options->repeat, "with --scene: render each method this many times (timing)")
        ->check(CLI::Range(1, 100));
    command->add_option("--lights", options->lights, "point lights")
        ->check(CLI::Range(1, 4))
        ->capture_default_str();
    add_shadow_map_options(*command, options->map_flags);
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
