// `tessera compare`: the user's own mesh or scene through both renderers, side by side (issue
// 18). For every --size and --threads: whole frames through the frame renderer (visibility,
// shading, the per-frame BVH, peak resident memory), the triangle ids of both visibility
// passes compared pixel for pixel, shadow maps against shadow rays when the content has lights
// (time and disagreement, render/renderer_comparison.h), and a BVH build against a refit.
// Times are medians of --repeat runs. --sweep repeats the content in a grid of copies to find
// where ray casting overtakes rasterization on this content (render/crossover.h); --json
// writes the figures with the machine, the command and the date, --plots draws them.
#include <tbb/global_control.h>
#include <tbb/info.h>

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "examples/command.h"
#include "examples/compare_plots.h"
#include "examples/compare_report.h"
#include "examples/machine.h"
#include "examples/model_view.h"
#include "examples/resident_memory.h"
#include "examples/shadow_map_flags.h"
#include "raster/asset/framing.h"
#include "raster/asset/light_rig.h"
#include "raster/core/atomic_file.h"
#include "raster/core/error.h"
#include "raster/embree/ray_cast.h"
#include "raster/pipeline/viewport.h"
#include "raster/render/frame_renderer.h"
#include "raster/scene/instance_grid.h"
#include "raster/scene_file/scene_build.h"
#include "raster/scene_file/scene_library.h"
#include "raster/scene_file/scene_parse.h"

namespace tessera::cli {
namespace {

struct Options {
    std::string mesh, scene;
    CameraFlags camera;
    std::string sizes = "1280x720", threads = "0", sweep;
    int repeat = 5;
    std::string json, plots;
    ShadowMapFlags map_flags;  // over every light's shadow-map settings
};

struct Size {
    int width, height;
};

// "A,B,C" into its parts; an empty part is an error naming the flag.
std::vector<std::string> split_list(const std::string& text, const char* flag) {
    std::vector<std::string> parts;
    size_t start = 0;
    for (;;) {
        const size_t comma = text.find(',', start);
        parts.push_back(text.substr(start, comma == std::string::npos ? std::string::npos : comma - start));
        if (parts.back().empty()) throw UsageError(std::string(flag) + " expects a comma-separated list, got '" + text + "'");
        if (comma == std::string::npos) return parts;
        start = comma + 1;
    }
}

std::vector<int> parse_counts(const std::string& text, const char* flag, int least, int most) {
    std::vector<int> counts;
    for (const std::string& part : split_list(text, flag)) {
        int value = 0;
        const auto [end, ec] = std::from_chars(part.data(), part.data() + part.size(), value);
        if (ec != std::errc() || end != part.data() + part.size() || value < least || value > most)
            throw UsageError(std::string(flag) + " expects whole numbers from " + std::to_string(least) + " to " +
                             std::to_string(most) + ", got '" + part + "'");
        counts.push_back(value);
    }
    return counts;
}

// The content as one animated scene, at the time it is compared.
struct Content {
    render::AnimatedScene scene;
    float time = 0.0f;
    // --mesh: lit by the default rig, which the sweep places again around the grid.
    bool default_rig = false;
};

Content load_content(const Options& o, Size first) {
    Content content;
    if (!o.mesh.empty()) {
        ModelView view = load_model_view(o.mesh, o.camera, first.width, first.height);
        content.scene = render::still_scene(std::move(view.scene));
        content.default_rig = true;
        o.map_flags.apply(content.scene.scene.lights);
        return content;
    }
    std::error_code ec;  // the running binary: scene folders next to an installed tessera
    const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
    const std::filesystem::path file =
        scene_file::find_scene(o.scene, scene_file::scene_directories(TESSERA_SCENE_DIR, ec ? "" : exe));
    std::vector<std::string> warnings;
    const scene_file::SceneSpec spec = scene_file::load_scene_file(file, warnings);
    content.scene = scene_file::build_scene(spec, &warnings);
    o.map_flags.apply(content.scene.scene.lights);
    for (const std::string& w : warnings) std::fprintf(stderr, "tessera: warning: %s\n", w.c_str());
    if (!spec.camera_given)
        std::fprintf(stderr, "tessera: camera (framed): %s\n", asset::camera_flags(content.scene.camera.camera).c_str());
    content.time = float(spec.animation.first) / spec.animation.fps;  // the first frame `tessera render` renders
    return content;
}

// The threads oneTBB runs with under the current cap (limit_threads).
int effective_threads() {
    const size_t cap = tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism);
    return int(std::min<size_t>(cap, size_t(tbb::info::default_concurrency())));
}

// Whole frames of `scene` through one renderer, `repeat` times after one that is not counted
// (it faults in the frame's buffers and the renderer's scratch memory): medians of the
// stages, and the peak resident memory while they ran.
RendererFigures time_frames(render::AnimatedScene& scene, Size size, render::RendererKind kind, int repeat, float time) {
    reset_peak_resident();
    render::FrameRenderer renderer(scene, size.width, size.height, kind, render::ShadowMode::none);
    std::vector<double> visibility, shading, bvh, total;
    Frame frame;
    renderer.render(time, frame);
    for (int r = 0; r < repeat; ++r) {
        render::FrameStats stats;
        renderer.render(time, frame, &stats);
        visibility.push_back(stats.visibility_ms);
        shading.push_back(stats.tiles_ms);
        bvh.push_back(stats.bvh_ms);
        total.push_back(stats.total_ms);
    }
    return {median(visibility), median(shading), median(bvh), median(total), peak_resident_mib()};
}

ConfigFigures measure(Content& content, Size size, int threads, int repeat) {
    const auto cap = limit_threads(threads);
    ConfigFigures c;
    c.width = size.width;
    c.height = size.height;
    c.threads = effective_threads();
    c.raster = time_frames(content.scene, size, render::RendererKind::raster, repeat, content.time);
    c.raytrace = time_frames(content.scene, size, render::RendererKind::raytrace, repeat, content.time);

    const render::StillFrame frame = render::still_frame(content.scene, content.time, size.width, size.height);
    const Mesh& mesh = frame.baked.mesh;
    const glm::mat4 vp = frame.camera.view_projection();
    const embree::RayDevice& device = embree::default_ray_device();
    const embree::RayScene rays(device, mesh);
    pipeline::Rasterizer rasterizer;
    VisibilityBuffer by_raster, by_rays;
    rasterizer.render(mesh, vp, pipeline::Viewport(size.width, size.height), pipeline::RasterOptions{}, by_raster);
    embree::cast_primary_rays(rays, vp, size.width, size.height, by_rays);
    c.ids = render::compare_triangle_ids(by_raster, by_rays);

    std::vector<double> build, refit, maps, shadow_rays;
    for (int r = 0; r < repeat; ++r) {
        const render::BvhTimes t = render::time_bvh(device, mesh);
        build.push_back(t.build_ms);
        refit.push_back(t.refit_ms);
    }
    c.bvh = {median(build), median(refit)};
    // Shadows as the frame renderer casts them: from at most 4 lights.
    const size_t lights = frame.light_targets.size();
    if (lights > 0 && lights <= 4) {
        ShadowFigures s;
        s.lights = lights;
        for (int r = 0; r < repeat; ++r) {
            const render::ShadowMethods m = render::compare_shadow_methods(rasterizer, rays, frame, by_raster);
            maps.push_back(m.maps_ms);
            shadow_rays.push_back(m.rays_ms);
            s.all = m.all;  // the same every run: the masks are deterministic
            s.non_grazing = m.non_grazing;
        }
        s.maps_ms = median(maps);
        s.rays_ms = median(shadow_rays);
        c.shadows = s;
    }
    return c;
}

// The bounds of the mesh's vertices, or none for an empty mesh.
std::optional<Box> vertex_bounds(const Mesh& mesh) {
    if (mesh.positions.empty()) return std::nullopt;
    Box box{mesh.positions.front(), mesh.positions.front()};
    for (const glm::vec3& p : mesh.positions) {
        box.lower = glm::min(box.lower, p);
        box.upper = glm::max(box.upper, p);
    }
    return box;
}

// --sweep: each count of copies in a grid (scene/instance_grid.h), framed as a whole.
std::vector<SweepPoint> sweep(Content& content, const std::vector<int>& counts, Size size, int threads, int repeat,
                              const ShadowMapFlags& map_flags) {
    const auto cap = limit_threads(threads);
    const float aspect = float(size.width) / float(size.height);
    content.scene.set_time(content.time, aspect);  // the copies are of the scene at this time
    const std::optional<Box> box = vertex_bounds(scene::bake(content.scene.scene).mesh);
    if (!box) throw Error("--sweep: the content has no triangles to copy");
    std::vector<SweepPoint> points;
    for (const int copies : counts) {
        const scene::InstanceGrid grid(copies, box->lower, box->upper);
        const auto [lower, upper] = grid.bounds(box->lower, box->upper);
        scene::Scene copied = scene::instance_grid(content.scene.scene, grid);
        copied.camera = asset::frame_box(lower, upper, aspect, content.scene.scene.camera.fovy_deg);
        if (content.default_rig) {
            copied.lights = asset::default_light_rig(copied.camera, lower, upper);
            map_flags.apply(copied.lights);
        }
        render::AnimatedScene still = render::still_scene(std::move(copied));
        SweepPoint p;
        p.copies = copies;
        p.raster = time_frames(still, size, render::RendererKind::raster, repeat, 0.0f);
        p.raytrace = time_frames(still, size, render::RendererKind::raytrace, repeat, 0.0f);
        p.triangles = scene::bake(still.scene).mesh.triangle_count();
        points.push_back(p);
    }
    return points;
}

// The command line as it was run, for the JSON file.
std::string command_line() {
    std::ifstream in("/proc/self/cmdline", std::ios::binary);
    std::string line, arg;
    while (std::getline(in, arg, '\0')) {
        if (!line.empty()) line += ' ';
        line += arg.find_first_of(" \t\"'") == std::string::npos ? arg : "'" + arg + "'";
    }
    return line;
}

std::string utc_now() {
    const std::time_t now = std::time(nullptr);
    std::tm utc{};
    gmtime_r(&now, &utc);
    char text[32];
    std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &utc);
    return text;
}

int run(const Options& o) {
    if (o.mesh.empty() == o.scene.empty()) throw UsageError("give one of --mesh FILE or --scene NAME|FILE");
    if (!o.scene.empty() && (!o.camera.file.empty() || !o.camera.eye.empty() || !o.camera.lookat.empty() ||
                             !o.camera.up.empty() || o.camera.fov || o.camera.near || o.camera.far))
        throw UsageError("the camera flags go with --mesh (a scene file has its own camera)");
    std::vector<Size> sizes;
    for (const std::string& part : split_list(o.sizes, "--size")) {
        Size s{};
        parse_size(part, "--size", s.width, s.height);
        (void)pipeline::Viewport(s.width, s.height);  // one pass: at most 8192 a side
        sizes.push_back(s);
    }
    const std::vector<int> threads = parse_counts(o.threads, "--threads", 0, 4096);
    std::vector<int> copies;
    if (!o.sweep.empty()) {
        copies = parse_counts(o.sweep, "--sweep", 1, 1'000'000);
        std::sort(copies.begin(), copies.end());
        copies.erase(std::unique(copies.begin(), copies.end()), copies.end());
    }
    // Outputs are checked before the work.
    if (!o.json.empty()) check_writable(o.json);
    if (!o.plots.empty()) check_plots(o.plots);

    Content content = load_content(o, sizes.front());
    ComparisonReport report;
    report.content = o.mesh.empty() ? o.scene : o.mesh;
    report.repeat = o.repeat;
    report.peak_per_renderer = reset_peak_resident();
    {
        content.scene.set_time(content.time, float(sizes.front().width) / float(sizes.front().height));
        report.triangles = scene::bake(content.scene.scene).mesh.triangle_count();
        report.lights = content.scene.scene.lights.size();
    }
    for (const Size size : sizes)
        for (const int t : threads) report.configs.push_back(measure(content, size, t, o.repeat));
    if (!copies.empty()) {
        report.sweep = sweep(content, copies, sizes.front(), threads.front(), o.repeat, o.map_flags);
        find_crossovers(report);
    }
    report.command = command_line();
    report.date = utc_now();
    report.cpu = cpu_model();
    report.simd = simd_target();
    report.hardware_threads = std::thread::hardware_concurrency();

    print_report(report);
    if (!o.json.empty()) write_file_atomically(o.json, report_json(report));
    if (!o.plots.empty()) {
        for (const std::string& written : write_plots(o.plots, report)) std::printf("plot: %s\n", written.c_str());
    }
    return 0;
}

Run define_compare(CLI::App& root) {
    auto options = std::make_shared<Options>();
    Options& o = *options;
    CLI::App* cmd = root.add_subcommand(
        "compare", "your mesh or scene through the rasterizer and the Embree ray caster, side by side");
    cmd->add_option("--mesh", o.mesh, "model file (OBJ, glTF, PLY...), framed and lit as `tessera raster --shade material`");
    cmd->add_option("--scene", o.scene, "built-in scene name or scene JSON file");
    add_camera_options(*cmd, o.camera);
    cmd->add_option("--size", o.sizes, "image sizes WxH[,WxH...] (at most 8192 a side)")->capture_default_str();
    cmd->add_option("--threads", o.threads, "thread counts N[,N...] (0 = all cores)")->capture_default_str();
    cmd->add_option("--repeat", o.repeat, "runs per measurement; times are their medians")
        ->check(CLI::Range(1, 1000))
        ->capture_default_str();
    cmd->add_option("--sweep", o.sweep,
                    "copies N1,N2,... of the content in a grid, framed as a whole: time against triangle count and "
                    "the crossover (at the first size and thread count)");
    add_shadow_map_options(*cmd, o.map_flags);
    cmd->add_option("--json", o.json, "write the figures, machine, command and date as JSON");
    cmd->add_option("--plots", o.plots, "write PNG plots into this folder (needs gnuplot)");
    return [options] { return run(*options); };
}

TESSERA_COMMAND(65, define_compare);

}  // namespace
}  // namespace tessera::cli
