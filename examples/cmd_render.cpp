// `tessera render`: renders frames of a built-in example scene through the tile rasterizer and
// the shading of raster/shade, writing each frame atomically.
//   tessera render --scene NAME | --obj FILE [--model M] [--size WxH] [--time T] [--frames N --fps F] [--cull MODE]
//                  [--cube-map 'DIR/{face}.png'] [--threads N] [--stats] --out FILE
// With --frames N > 1, FILE must hold one frame number ("f_####.png" or "f_%04d.png"); frame i
// shows the scene at time T + i / F. The extension picks the encoding (frame.h: .png 8-bit sRGB,
// .exr float linear, .tif 16-bit sRGB).
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>

#include "examples/command.h"
#include "examples/example_scenes.h"
#include "raster/image_io.h"
#include "raster/output/frame.h"
#include "raster/output/frame_sequence.h"
#include "raster/output/frame_writer.h"
#include "raster/shade/scene_renderer.h"

namespace tessera::cli {
namespace {

struct Options {
    std::string scene;
    std::string size = "960x540";
    float time = 0.0f;
    int frames = 1;
    float fps = 24.0f;
    std::string cull = "none";
    std::string out;
    std::string cube_map;
    std::string obj;
    std::string model = "phong";
    int threads = 0;
    bool stats = false;
};

void check(const Options& o, int& width, int& height) {
    if (o.scene.empty() == o.obj.empty()) {
        std::string names;
        for (const std::string& n : examples::scene_names()) names += (names.empty() ? "" : ", ") + n;
        throw UsageError("give either --scene NAME (" + names + ") or --obj FILE");
    }
    parse_size(o.size, "--size", width, height);
    if (o.out.empty()) throw UsageError("--out FILE is required");
    if (o.frames > 1 && !FramePattern(o.out).has_placeholder())
        throw UsageError("--out '" + o.out + "' needs exactly one frame number (#### or %04d) when --frames > 1");
    if (!image_format_supported(o.out))
        throw UsageError("cannot write '" + o.out + "': no image format for extension '" +
                         std::filesystem::path(o.out).extension().string() + "' (use .png, .exr or .tif)");
    if (!std::isfinite(o.time) || !std::isfinite(o.fps) || o.fps <= 0.0f)
        throw UsageError("--time must be finite and --fps positive");
}

int run(const Options& o) {
    int width = 0, height = 0;
    check(o, width, height);
    SceneRenderOptions options;
    options.cull = o.cull == "back" ? CullMode::back : o.cull == "front" ? CullMode::front : CullMode::none;
    const auto limit = limit_threads(o.threads);
    Scene scene = o.obj.empty() ? examples::make_scene(o.scene)
                                : examples::obj_scene(o.obj, parse_shading_model(o.model));
    if (!o.cube_map.empty()) {
        scene.background.kind = Background::Kind::cube_map;
        scene.background.cube = load_cube_map(o.cube_map);
    }
    scene.camera.aspect = float(width) / float(height);
    SceneRenderer renderer;
    const FramePattern pattern(o.out);
    FrameWriter writer;  // encodes and writes frame i while frame i + 1 renders
    for (int i = 0; i < o.frames; ++i) {
        scene.animate(o.time + float(i) / o.fps);
        RasterStats stats;
        const Frame frame = renderer.render(scene, width, height, options, &stats);
        const std::filesystem::path path = pattern.has_placeholder() ? pattern.path_for(i) : std::filesystem::path(o.out);
        writer.submit(path, encode_frame(path, frame));
        if (o.stats)
            std::printf("%s: %llu triangles, %llu visible pixels, raster %.1f ms, shading %.1f ms, total %.1f ms\n",
                        path.string().c_str(), (unsigned long long)stats.triangles, (unsigned long long)stats.visible_pixels,
                        stats.vertex_ms + stats.setup_bin_ms + stats.raster_ms, stats.passes_ms, stats.total_ms);
    }
    writer.finish();
    return 0;
}

Run define_render(CLI::App& root) {
    auto o = std::make_shared<Options>();
    CLI::App* cmd = root.add_subcommand("render", "render frames of an example scene (flag, toon, bumpcube, snakes)");
    cmd->add_option("--scene", o->scene, "scene name: flag, toon, bumpcube or snakes");
    cmd->add_option("--size", o->size, "frame size WxH")->default_val("960x540");
    cmd->add_option("--time", o->time, "scene time of the first frame, seconds")->default_val(0.0f);
    cmd->add_option("--frames", o->frames, "number of frames")->check(CLI::Range(1, 1000000))->default_val(1);
    cmd->add_option("--fps", o->fps, "frames per second of scene time")->default_val(24.0f);
    cmd->add_option("--cull", o->cull, "back-face culling: none, back or front")
        ->check(CLI::IsMember({"none", "back", "front"}))
        ->default_val("none");
    cmd->add_option("--out", o->out, "output image (.png, .exr, .tif); a #### or %04d pattern for several frames");
    cmd->add_option("--obj", o->obj, "render a Wavefront OBJ file instead of a built-in scene");
    cmd->add_option("--model", o->model, "shading model for --obj: flat, gouraud, phong or toon")
        ->default_val("phong");
    cmd->add_option("--cube-map", o->cube_map,
                    "environment from six images, e.g. 'sky/{face}.png' ({face}: px nx py ny pz nz)");
    cmd->add_flag("--stats", o->stats, "print per-frame counts and times");
    add_threads_option(*cmd, o->threads);
    return [o] { return run(*o); };
}

TESSERA_COMMAND(20, define_render);

}  // namespace
}  // namespace tessera::cli
