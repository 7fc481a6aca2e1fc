// `tessera raster`: renders one mesh with one camera through the tile rasterizer (issue 3),
// or with --renderer raytrace through Embree primary rays (issue 6): same visibility buffer,
// same shading passes, same outputs.
// Used by other tools for conformance (Mesa llvmpipe comparison) and benchmarking, so its flags,
// file formats and the `frame_ms median=X min=Y max=Z` line are a contract.
// --shade material renders the model with its own materials instead (issue 18): the scene
// renderer both renderers share (render/frame_renderer.h), lit by the default light rig.
// --shade id --samples N finds visibility per sample and writes every sample's id (--out-id),
// for the comparison with the peer's multisampled ids (issue 17).
#include <algorithm>
#include <chrono>
#include <memory>
#include <span>
#include <cstdio>
#include <vector>

#include "examples/command.h"
#include "examples/shadow_map_flags.h"
#include "examples/model_view.h"
#include "raster/core/atomic_file.h"
#include "raster/embree/ray_cast.h"
#include "raster/embree/scene.h"
#include "raster/embree/tile_passes.h"
#include "raster/io/image_io.h"
#include "raster/pipeline/rasterizer.h"
#include "raster/shade/reference_shading.h"
#include "raster/shade/depth_view.h"
#include "raster/shade/stamp_shading.h"
#include "raster/io/visibility_io.h"
#include "raster/output/frame_encoding.h"
#include "raster/render/frame_renderer.h"

namespace tessera::cli {
namespace {

struct Options {
    std::string mesh, size = "1920x1080";
    CameraFlags camera;
    std::string shade = "phong", cull = "none";
    int threads = 0;
    std::string out_color, out_id, out_depth;
    int repeat = 0;
    bool stats = false;
    int tile = 0;
    std::string renderer = "raster";
    std::string shadows = "none";
    int samples = 1;
    ShadowMapFlags map_flags;
};

void print_stats(const pipeline::RasterStats& s, double shade_ms) {
    std::printf("stats: vertex_ms=%.3f clip_setup_bin_ms=%.3f raster_ms=%.3f shade_ms=%.3f total_ms=%.3f\n",
                s.vertex_ms, s.setup_bin_ms, s.raster_ms, shade_ms, s.total_ms);
    std::printf("stats: triangles_in=%llu invalid=%llu outside=%llu clipped=%llu zero_area=%llu "
                "culled_face=%llu no_samples=%llu setups=%llu binned=%llu pixels_shaded=%llu\n",
                (unsigned long long)s.triangles, (unsigned long long)s.invalid, (unsigned long long)s.outside,
                (unsigned long long)s.clipped, (unsigned long long)s.zero_area, (unsigned long long)s.culled_face,
                (unsigned long long)s.no_samples, (unsigned long long)s.setups, (unsigned long long)s.bin_entries,
                (unsigned long long)s.visible_pixels);
}

// --shade material: the model's scene through the frame renderer.
int run_material(const Options& o, int width, int height) {
    if (!o.out_id.empty() || !o.out_depth.empty() || o.cull != "none" || o.tile)
        throw UsageError("--out-id, --out-depth, --cull and --tile go with --shade id|depth|normal|phong");
    if (!o.out_color.empty() && !output::frame_format_supported(o.out_color))
        throw UsageError("--out-color: no image writer for '" + o.out_color + "'");
    if (!o.out_color.empty()) check_writable(o.out_color);  // before the work
    const pipeline::Viewport viewport(width, height);  // checks the size limits
    ModelView view = load_model_view(o.mesh, o.camera, width, height);
    const auto threads = limit_threads(o.threads);
    render::AnimatedScene scene = render::still_scene(std::move(view.scene));
    o.map_flags.apply(scene.scene.lights);
    render::FrameRenderer renderer(scene, width, height, render::parse_renderer(o.renderer),
                                   render::parse_shadow_mode(o.shadows), o.samples);
    std::vector<double> frame_ms;
    render::FrameStats stats;
    Frame frame(1, 1);
    for (int f = 0; f < std::max(1, o.repeat); ++f) {
        frame = renderer.render(0.0f, &stats);
        frame_ms.push_back(stats.total_ms);
    }
    if (!o.out_color.empty()) output::write_frame(o.out_color, frame);
    if (o.repeat > 0) print_frame_times(frame_ms);
    if (o.stats) {
        std::printf("stats: model_triangles=%zu model_vertices=%zu skipped_triangles=%zu skipped_primitives=%zu "
                    "read_ms=%.3f convert_ms=%.3f\n",
                    view.stats.triangles, view.stats.vertices, view.stats.skipped_triangles,
                    view.stats.skipped_primitives, view.stats.read_ms, view.stats.convert_ms);
        std::printf("stats: bake_ms=%.3f bvh_ms=%.3f visibility_ms=%.3f tiles_ms=%.3f total_ms=%.3f "
                    "shadowed_pixels=%llu\n",
                    stats.bake_ms, stats.bvh_ms, stats.visibility_ms, stats.tiles_ms, stats.total_ms,
                    (unsigned long long)stats.shadowed_pixels);
        // The tile stage by pass, thread time summed over the tiles (render/tile_pass_times.h).
        std::printf("stats: tiles_thread_ms=%.3f", stats.tile_passes.tiles_ms);
        for (size_t p = 0; p < render::kTilePasses; ++p)
            std::printf(" %s_ms=%.3f", std::string(render::tile_pass_name(render::TilePass(p))).c_str(), stats.tile_passes.ms[p]);
        std::printf("\n");
    }
    return 0;
}

int run(const Options& o) {
    int width = 0, height = 0;
    parse_size(o.size, "--size", width, height);
    if (o.shade == "material") return run_material(o, width, height);
    if (o.shadows != "none") throw UsageError("--shadows goes with --shade material");
    const pipeline::CullMode cull = parse_cull(o.cull);
    const shade::ShadeMode shade = shade::parse_shade_mode(o.shade);
    // The conformance shaders are defined at pixel centres, as their peer renders them; with
    // --samples only visibility is multisampled, for the per-sample ids the peer's multisampled
    // ids are compared with: --shade id, and no colour or depth image.
    const bool multisampled = o.samples > 1;
    if (multisampled && shade != shade::ShadeMode::id)
        throw UsageError("--samples goes with --shade id (per-sample ids) or --shade material");
    if (multisampled && (!o.out_color.empty() || !o.out_depth.empty()))
        throw UsageError("--shade id --samples N writes per-sample ids (--out-id), not --out-color or --out-depth");
    if (!o.out_color.empty() && !io::image_format_supported(o.out_color))
        throw UsageError("--out-color: no image writer for '" + o.out_color + "'");
    for (const std::string* path : {&o.out_color, &o.out_id, &o.out_depth})  // before the work
        if (!path->empty()) check_writable(*path);
    const pipeline::Viewport viewport(width, height);  // checks the size limits

    const bool raytrace = o.renderer == "raytrace";
    if (raytrace && (cull != pipeline::CullMode::none || o.tile))
        throw UsageError("--cull and --tile apply to --renderer raster only");

    ModelMesh model = load_model_mesh(o.mesh);
    Mesh& mesh = model.mesh;
    const Camera camera = make_camera_or_frame(o.camera, width, height, model.box);
    // An OBJ that is no OBJ at all (another text file, say) reads as an empty mesh: say so.
    if (mesh.indices.empty())
        std::fprintf(stderr, "tessera: warning: '%s' yields no geometry (no faces); the image is empty\n",
                     o.mesh.c_str());
    if (raytrace) embree::reserve_ray_padding(mesh);  // lets Embree share the vertex buffer
    const auto threads = limit_threads(o.threads);

    pipeline::RasterOptions options;
    options.cull = cull;
    if (o.tile) options.tile_size = o.tile;
    options.tile_color = false;  // the pass writes rgba8 itself
    // The frame's visibility buffer only where something reads it after the tiles: the id and
    // depth files, and the depth view (its grey range spans the whole frame). Otherwise each
    // tile is shaded from its cache-resident buffers and only finished pixels reach memory.
    options.frame_visibility = !o.out_id.empty() || !o.out_depth.empty() || shade == shade::ShadeMode::depth;
    if (multisampled) {
        // Visibility per sample and no shading pass (RasterOptions::samples asks for the
        // colour tile, which no pass then writes).
        options.samples = o.samples;
        options.tile_color = true;
        options.frame_visibility = true;
        options.keep_samples = !o.out_id.empty();
    }
    pipeline::Rasterizer rasterizer;
    VisibilityBuffer visibility;
    std::vector<uint32_t> rgba8(size_t(width) * height);
    const pipeline::TilePass shading[] = {shade::make_stamp_shading_pass(shade, camera, rgba8)};
    const std::span<const pipeline::TilePass> passes = multisampled ? std::span<const pipeline::TilePass>() : shading;
    const glm::mat4 view_projection = camera.view_projection();

    const int frames = std::max(1, o.repeat);
    std::vector<double> frame_ms;
    pipeline::RasterStats stats;
    // The ray-cast frame: BVH built once (static mesh), then per frame primary rays and the
    // same tile passes. Its --stats line reports the BVH and the mesh defects Embree skips.
    std::unique_ptr<embree::RayScene> scene;
    double build_ms = 0, trace_ms = 0, shade_ms = 0;
    if (raytrace) {
        const embree::RayDevice& device = embree::default_ray_device();  // created outside the timing
        const auto start = std::chrono::steady_clock::now();
        scene = std::make_unique<embree::RayScene>(device, mesh);
        build_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    }
    for (int f = 0; f < frames; ++f) {
        const auto start = std::chrono::steady_clock::now();
        if (raytrace) {
            embree::cast_primary_rays(*scene, view_projection, width, height, visibility, embree::RayPacket::x16, {},
                                      o.samples);
            const auto traced = std::chrono::steady_clock::now();
            if (!passes.empty()) embree::run_tile_passes(mesh, view_projection, viewport, visibility, passes);
            trace_ms = std::chrono::duration<double, std::milli>(traced - start).count();
            shade_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - traced).count();
        } else {
            rasterizer.render(mesh, view_projection, viewport, options, visibility, passes, nullptr, &stats);
        }
        frame_ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
    }

    if (!o.out_color.empty()) {
        std::vector<uint8_t> rgb8;
        // The tile pass wrote grey = window depth; the picture maps the visible distances instead.
        if (shade == shade::ShadeMode::depth) shade::depth_view(visibility, camera, rgb8);
        else rgb8 = shade::rgb8_of(rgba8);
        io::write_image(o.out_color, io::ImageView{width, height, 3, io::PixelType::u8, rgb8.data(), /*srgb=*/true});
    }
    if (!o.out_id.empty()) io::write_tsid(o.out_id, visibility);
    if (!o.out_depth.empty()) io::write_depth_pfm(o.out_depth, visibility);

    if (o.repeat > 0) print_frame_times(frame_ms);
    if (o.stats) {
        const io::ObjLoadStats& load = model.obj_stats;
        if (model.obj)
            std::printf("stats: obj_faces=%zu obj_triangles=%zu bad_vertices=%zu skipped_triangles=%zu\n",
                        load.faces, load.triangles, load.bad_vertices, load.skipped_triangles);
        else
            std::printf("stats: model_triangles=%zu model_vertices=%zu skipped_triangles=%zu skipped_primitives=%zu "
                        "read_ms=%.3f convert_ms=%.3f\n",
                        model.model_stats.triangles, model.model_stats.vertices, model.model_stats.skipped_triangles,
                        model.model_stats.skipped_primitives, model.model_stats.read_ms,
                        model.model_stats.convert_ms);
        if (raytrace) {
            const embree::MeshDefects& d = scene->defects();
            std::printf("stats: bvh_build_ms=%.3f trace_ms=%.3f shade_ms=%.3f\n", build_ms, trace_ms, shade_ms);
            std::printf("stats: triangles_in=%zu nonfinite=%zu bad_index=%zu degenerate=%zu\n",
                        mesh.triangle_count(), d.nonfinite, d.bad_index, d.degenerate);
        } else {
            print_stats(stats, stats.passes_ms);
        }
    }
    return 0;
}

Run define_raster(CLI::App& root) {
    auto options = std::make_shared<Options>();
    Options& o = *options;
    CLI::App* cmd = root.add_subcommand("raster", "render one mesh with one camera through the tile rasterizer");
    cmd->add_option("--mesh", o.mesh,
                    "model file: OBJ (faces fan-triangulated; triangle id = order in file), glTF 2.0 "
                    "(.gltf/.glb), PLY, STL, FBX... (through Assimp; parts in node order)")
        ->required();
    cmd->add_option("--size", o.size, "image size WIDTHxHEIGHT (at most 8192x8192)")->default_val("1920x1080");
    add_camera_options(*cmd, o.camera);
    cmd->add_option("--shade", o.shade,
                    "id | depth | normal | phong | material (the model's own materials, default light rig)")
        ->default_val("phong");
    cmd->add_option("--shadows", o.shadows, "none | map | rays (with --shade material)")
        ->check(CLI::IsMember({"none", "map", "rays"}))
        ->default_val("none");
    add_samples_option(*cmd, o.samples,
                       "(with --shade material; with --shade id, --out-id writes every sample's id; default 1)");
    add_shadow_map_options(*cmd, o.map_flags);
    cmd->add_option("--cull", o.cull, "none | back | front (front faces are counter-clockwise)")->default_val("none");
    add_threads_option(*cmd, o.threads);
    cmd->add_option("--out-color", o.out_color, "colour image (PNG, EXR, TIFF...; 8-bit RGB)");
    cmd->add_option("--out-id", o.out_id, "triangle ids (TSID: header, then uint32 LE per pixel, or per sample with --samples)");
    cmd->add_option("--out-depth", o.out_depth, "window depth (PFM, rows bottom to top)");
    cmd->add_option("--repeat", o.repeat, "render K frames and print 'frame_ms median=X min=Y max=Z'")
        ->check(CLI::Range(1, 100000));
    cmd->add_flag("--stats", o.stats, "print per-stage times and counts");
    cmd->add_option("--renderer", o.renderer, "raster | raytrace (Embree primary rays, same shading)")
        ->check(CLI::IsMember({"raster", "raytrace"}))
        ->default_val("raster");
    cmd->add_option("--tile", o.tile, "tile size in pixels (16..256, power of two; for measurements)")
        ->check(CLI::IsMember({16, 32, 64, 128, 256}));
    return [options] { return run(*options); };
}

TESSERA_COMMAND(20, define_raster);

}  // namespace
}  // namespace tessera::cli
