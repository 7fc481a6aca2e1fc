// `tessera raster`: renders one OBJ mesh with one camera through the tile rasterizer (issue 3).
// Used by other tools for conformance (Mesa llvmpipe comparison) and benchmarking, so its flags,
// file formats and the `frame_ms median=X min=Y max=Z` line are a contract.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <sstream>
#include <vector>

#include "examples/command.h"
#include "raster/camera_file.h"
#include "raster/image_io.h"
#include "raster/obj_loader.h"
#include "raster/rasterizer.h"
#include "raster/reference_shading.h"
#include "raster/visibility_io.h"

namespace tessera::cli {
namespace {

// "x,y,z" -> vec3, or a UsageError naming the flag.
glm::vec3 parse_vec3(const std::string& text, const char* flag) {
    std::istringstream in(text);
    glm::vec3 v;
    char c1 = 0, c2 = 0;
    std::string rest;
    if (!(in >> v.x >> c1 >> v.y >> c2 >> v.z) || c1 != ',' || c2 != ',' || (in >> rest))
        throw UsageError(std::string(flag) + " expects x,y,z, got '" + text + "'");
    return v;
}

struct Options {
    std::string mesh, camera_file, size = "1920x1080";
    std::string eye, lookat, up;
    float fov = 0, near = 0, far = 0;
    bool has_fov = false, has_near = false, has_far = false;
    std::string shade = "phong", cull = "none";
    int threads = 0;
    std::string out_color, out_id, out_depth;
    int repeat = 0;
    bool stats = false;
    int tile = 0;
};

CullMode parse_cull(const std::string& text) {
    if (text == "none") return CullMode::none;
    if (text == "back") return CullMode::back;
    if (text == "front") return CullMode::front;
    throw UsageError("--cull expects none, back or front, got '" + text + "'");
}

void print_stats(const RasterStats& s, double shade_ms) {
    std::printf("stats: vertex_ms=%.3f clip_setup_bin_ms=%.3f raster_ms=%.3f shade_ms=%.3f total_ms=%.3f\n",
                s.vertex_ms, s.setup_bin_ms, s.raster_ms, shade_ms, s.total_ms);
    std::printf("stats: triangles_in=%llu invalid=%llu outside=%llu clipped=%llu zero_area=%llu "
                "culled_face=%llu no_samples=%llu setups=%llu binned=%llu pixels_shaded=%llu\n",
                (unsigned long long)s.triangles, (unsigned long long)s.invalid, (unsigned long long)s.outside,
                (unsigned long long)s.clipped, (unsigned long long)s.zero_area, (unsigned long long)s.culled_face,
                (unsigned long long)s.no_samples, (unsigned long long)s.setups, (unsigned long long)s.bin_entries,
                (unsigned long long)s.visible_pixels);
}

int run(const Options& o) {
    int width = 0, height = 0;
    parse_size(o.size, "--size", width, height);
    const CullMode cull = parse_cull(o.cull);
    const ShadeMode shade = parse_shade_mode(o.shade);
    for (const std::string* path : {&o.out_color})
        if (!path->empty() && !image_format_supported(*path))
            throw UsageError("--out-color: no image writer for '" + *path + "'");
    const Viewport viewport(width, height);  // checks the size limits

    Camera camera;
    if (!o.camera_file.empty()) read_camera_file(o.camera_file, camera);
    if (!o.eye.empty()) camera.eye = parse_vec3(o.eye, "--eye");
    if (!o.lookat.empty()) camera.lookat = parse_vec3(o.lookat, "--lookat");
    if (!o.up.empty()) camera.up = parse_vec3(o.up, "--up");
    if (o.has_fov) camera.fovy_deg = o.fov;
    if (o.has_near) camera.near = o.near;
    if (o.has_far) camera.far = o.far;
    camera.aspect = float(width) / float(height);
    validate_camera(camera);

    ObjLoadStats load;
    const Mesh mesh = load_obj(o.mesh, &load);
    const auto threads = limit_threads(o.threads);

    RasterOptions options;
    options.cull = cull;
    if (o.tile) options.tile_size = o.tile;
    Rasterizer rasterizer;
    VisibilityBuffer visibility;
    std::vector<uint8_t> rgb8(size_t(width) * height * 3);
    const TilePass passes[] = {make_reference_shading_pass(shade, camera, rgb8)};
    const glm::mat4 view_projection = camera.view_projection();

    const int frames = std::max(1, o.repeat);
    std::vector<double> frame_ms;
    RasterStats stats;
    for (int f = 0; f < frames; ++f) {
        const auto start = std::chrono::steady_clock::now();
        rasterizer.render(mesh, view_projection, viewport, options, visibility, passes, nullptr, &stats);
        frame_ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
    }

    if (!o.out_color.empty())
        write_image(o.out_color, ImageView{width, height, 3, PixelType::u8, rgb8.data()});
    if (!o.out_id.empty()) write_tsid(o.out_id, visibility);
    if (!o.out_depth.empty()) write_depth_pfm(o.out_depth, visibility);

    if (o.repeat > 0) {
        std::vector<double> sorted = frame_ms;
        std::sort(sorted.begin(), sorted.end());
        const size_t n = sorted.size();
        const double median = n % 2 ? sorted[n / 2] : 0.5 * (sorted[n / 2 - 1] + sorted[n / 2]);
        std::printf("frame_ms median=%.3f min=%.3f max=%.3f\n", median, sorted.front(), sorted.back());
    }
    if (o.stats) {
        std::printf("stats: obj_faces=%zu obj_triangles=%zu bad_vertices=%zu skipped_triangles=%zu\n", load.faces,
                    load.triangles, load.bad_vertices, load.skipped_triangles);
        print_stats(stats, stats.passes_ms);
    }
    return 0;
}

Run define_raster(CLI::App& root) {
    auto options = std::make_shared<Options>();
    Options& o = *options;
    CLI::App* cmd = root.add_subcommand("raster", "render one OBJ mesh with one camera through the tile rasterizer");
    cmd->add_option("--mesh", o.mesh, "OBJ file (faces fan-triangulated; triangle id = order in file)")->required();
    cmd->add_option("--camera", o.camera_file, "camera file: lines 'eye x y z', 'lookat x y z', 'up x y z', "
                                               "'fovy_deg f', 'near n', 'far f'");
    cmd->add_option("--size", o.size, "image size WIDTHxHEIGHT (at most 8192x8192)")->default_val("1920x1080");
    cmd->add_option("--eye", o.eye, "camera position x,y,z (overrides the file)");
    cmd->add_option("--lookat", o.lookat, "point looked at x,y,z");
    cmd->add_option("--up", o.up, "up direction x,y,z");
    cmd->add_option_function<float>("--fov", [&o](float v) { o.fov = v; o.has_fov = true; }, "vertical field of view, degrees");
    cmd->add_option_function<float>("--near", [&o](float v) { o.near = v; o.has_near = true; }, "near plane distance");
    cmd->add_option_function<float>("--far", [&o](float v) { o.far = v; o.has_far = true; }, "far plane distance");
    cmd->add_option("--shade", o.shade, "id | depth | normal | phong")->default_val("phong");
    cmd->add_option("--cull", o.cull, "none | back | front (front faces are counter-clockwise)")->default_val("none");
    add_threads_option(*cmd, o.threads);
    cmd->add_option("--out-color", o.out_color, "colour image (PNG, EXR, TIFF...; 8-bit RGB)");
    cmd->add_option("--out-id", o.out_id, "triangle ids (TSID: header, then uint32 LE per pixel)");
    cmd->add_option("--out-depth", o.out_depth, "window depth (PFM, rows bottom to top)");
    cmd->add_option("--repeat", o.repeat, "render K frames and print 'frame_ms median=X min=Y max=Z'")
        ->check(CLI::Range(1, 100000));
    cmd->add_flag("--stats", o.stats, "print per-stage times and counts");
    cmd->add_option("--tile", o.tile, "tile size in pixels (16..256, power of two; for measurements)")
        ->check(CLI::IsMember({16, 32, 64, 128, 256}));
    return [options] { return run(*options); };
}

TESSERA_COMMAND(20, define_raster);

}  // namespace
}  // namespace tessera::cli
