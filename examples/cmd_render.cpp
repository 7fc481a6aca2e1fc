// `tessera render`: animation frames of a scene file.
//   tessera render --scene NAME|FILE.json [--size WxH] [--frames A:B] [--fps F]
//                  [--out out/NAME_####.png|.exr|.tif] [--threads N]
//                  [--renderer raster|raytrace] [--shadows none|map|rays]
//                  [--png fast|small] [--resume] [--shard I/N] [--stats] [--trace FILE.json]
//                  [--quiet]
// Frames are encoded and written on a background thread (FrameWriter) while the next one
// renders, each atomically (temp name + rename), so an interrupted run leaves only complete
// frames and --resume skips them. Frames beyond one 8192x8192 pass are rendered band by band
// and streamed into their file (FrameRenderer::render_bands, FrameStream), so memory holds a
// band, not the frame. Ctrl-C finishes the frame in hand, waits for the writer and exits 130.
// Exit codes as every command: 2 for bad flags, 1 for a failed run.
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstring>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "examples/command.h"
#include "examples/distribute.h"
#include "examples/progress.h"
#include "examples/render_farm.h"
#include "raster/asset/framing.h"
#include "raster/core/error.h"
#include "examples/farm/frame_claim.h"
#include "raster/io/image_io.h"
#include "raster/output/frame_encoding.h"
#include "raster/output/frame_stream.h"
#include "examples/frame_sequence.h"
#include "raster/output/frame_writer.h"
#include "raster/render/frame_renderer.h"
#include "raster/scene_file/scene_build.h"
#include "raster/scene_file/scene_library.h"
#include "raster/scene_file/scene_parse.h"
#include "raster/core/trace.h"

namespace tessera::cli {
namespace {

namespace fs = std::filesystem;

// Set by SIGINT, read between frames: the render stops after the frame in hand. The default
// action comes back at once, so a second Ctrl-C ends a frame that takes too long.
volatile std::sig_atomic_t g_interrupted = 0;
extern "C" void on_interrupt(int) {
    g_interrupted = 1;
    std::signal(SIGINT, SIG_DFL);
}

// Frames up to 8K (and anything within one 8192 x 8192 viewport) are rendered whole in memory
// and written by the background FrameWriter; larger ones are rendered band by band and
// streamed into the file (band_layout.h, image_stream.h), up to this size per side.
constexpr int kMaxSide = 65536;

struct Options {
    std::string scene = "snakes";
    std::string size, frames, out, renderer = "raster", shadows, shard = "0/1", trace, png = "fast";
    float fps = 0.0f;
    int threads = 0;
    bool resume = false, stats = false, quiet = false;
    FarmOptions farm;  // --claim, --checkpoint-every, --distribute (render_farm.h)
};

// Fails before any rendering when the output directory cannot take files.
void prepare_output_directory(const fs::path& first_file) {
    const fs::path dir = first_file.parent_path().empty() ? fs::path(".") : first_file.parent_path();
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (!fs::is_directory(dir))
        throw Error("cannot write frames to '" + dir.string() + "': " + (ec ? ec.message() : "not a directory"));
    if (access(dir.c_str(), W_OK) != 0)
        throw Error("cannot write frames to '" + dir.string() + "': permission denied");
}

// A run killed mid-write (SIGKILL, power loss) leaves its temporary ".NAME.tmpPID_N" beside
// the frame (atomic_file.h). --resume removes those of its own frames: other shards render
// other frames, so their temporaries have other names and are never touched.
void remove_stale_temporaries(const std::vector<fs::path>& frames) {
    std::map<fs::path, std::set<std::string>> names;  // directory -> frame file names
    for (const fs::path& f : frames)
        names[f.parent_path().empty() ? fs::path(".") : f.parent_path()].insert(f.filename().string());
    std::error_code ec;
    for (const auto& [dir, wanted] : names) {
        std::vector<fs::path> stale;
        for (const auto& entry : fs::directory_iterator(dir, ec)) {
            const std::string n = entry.path().filename().string();
            const size_t tmp = n.rfind(".tmp");
            if (n.size() > 1 && n[0] == '.' && tmp != std::string::npos && wanted.count(n.substr(1, tmp - 1)))
                stale.push_back(entry.path());
        }
        for (const fs::path& p : stale) fs::remove(p, ec);
    }
}

int run(const Options& o, const std::string& executable) {
    const auto guard = limit_threads(o.threads);
    // Scene.
    const fs::path file = scene_file::find_scene(o.scene, scene_file::scene_directories(TESSERA_SCENE_DIR, executable));
    std::vector<std::string> warnings;
    scene_file::SceneSpec spec = scene_file::load_scene_file(file, warnings);
    for (const std::string& w : warnings) std::fprintf(stderr, "tessera: warning: %s\n", w.c_str());
    const std::string scene_name = file.stem().string();

    // Flags over the scene's defaults, all checked before any work.
    int width = spec.size.x, height = spec.size.y;
    if (!o.size.empty()) parse_size(o.size, "--size", width, height);
    if (width > kMaxSide || height > kMaxSide)
        throw UsageError("--size " + std::to_string(width) + "x" + std::to_string(height) + ": at most " +
                         std::to_string(kMaxSide) + " pixels per side");
    FrameRange range{spec.animation.first, spec.animation.last};
    if (!o.frames.empty()) range = parse_frame_range(o.frames);
    const Shard shard = parse_shard(o.shard);
    const float fps = o.fps > 0.0f ? o.fps : spec.animation.fps;
    if (!(fps > 0.0f) || !std::isfinite(fps)) throw UsageError("--fps must be positive");
    const FramePattern pattern(o.out.empty() ? "out/" + scene_name + "_####.png" : o.out);
    if (!pattern.has_placeholder() && range.count() > 1)
        throw UsageError("--out '" + pattern.text() + "' has no #### or %04d, but " + std::to_string(range.count()) +
                         " frames would overwrite it");
    if (!io::image_format_supported(pattern.path_for(range.first)))
        throw UsageError("--out '" + pattern.text() + "': no image format for that extension (use .png, .exr or .tif)");
    const render::RendererKind renderer = render::parse_renderer(o.renderer);
    const render::ShadowMode shadows = render::parse_shadow_mode(o.shadows.empty() ? spec.shadows : o.shadows);
    const DistributeMode mode = parse_distribute(o.farm.distribute);
    if (mode == DistributeMode::tiles && o.farm.claim)
        throw UsageError("--claim works on whole frames: not with --distribute tiles");

    prepare_output_directory(pattern.path_for(range.first));
    std::vector<int> frames;
    int skipped = 0;
    const std::vector<int> shard_frames = frames_of_shard(range, shard);
    if (o.resume && !o.farm.claim) {  // with --claim, a frame's temporaries go when its claim is won
        std::vector<fs::path> paths;
        for (int f : shard_frames) paths.push_back(pattern.path_for(f));
        remove_stale_temporaries(paths);
    }
    for (int f : shard_frames) {
        const fs::path path = pattern.path_for(f);
        if (!(o.resume && io::image_is_complete(path, width, height))) {
            frames.push_back(f);
            continue;
        }
        ++skipped;
        // A process killed between publishing a frame and removing its claim leaves the claim
        // behind: break it by the usual protocol (stale owners only) and hand it straight back.
        if (o.farm.claim &&
            farm::try_claim(path, {true, o.farm.claim_timeout}) != farm::ClaimResult::held)
            farm::release_claim(path);
    }

    const std::unique_ptr<Distribution> distribution = make_distribution(mode, std::move(frames));
    Distribution& dist = *distribution;
    const bool rank0 = dist.rank() == 0;

    Trace trace;
    if (!o.trace.empty()) trace.activate();
    render::AnimatedScene scene = [&] {
        TraceScope t("build scene");
        std::vector<std::string> build_warnings;
        render::AnimatedScene built = scene_file::build_scene(spec, &build_warnings);
        if (rank0) {
            for (const std::string& w : build_warnings) std::fprintf(stderr, "tessera: warning: %s\n", w.c_str());
            if (!spec.camera_given)
                std::fprintf(stderr, "tessera: camera (framed): %s\n", asset::camera_flags(built.camera.camera).c_str());
        }
        return built;
    }();
    render::FrameRenderer frame_renderer(scene, width, height, renderer, shadows);
    output::FrameWriter writer(2, output::FileSettings{output::parse_png_compression(o.png)});
    FarmRun farm(o.farm, o.resume, scene, spec.textures, scene_name, pattern.path_for(range.first));
    const bool banded = render::needs_bands(width, height);
    const render::BandLayout layout = render::band_layout(width, height);
    if (!banded) {
        const auto [rows_first, rows_last] = dist.rows(height);
        frame_renderer.set_rows(rows_first, rows_last);
    }
    // Distributed: a failure is handed to rank 0 (which names the rank and the frame) instead
    // of ending this rank alone. A failed write names the first frame not yet on disk.
    std::vector<std::pair<fs::path, int>> submitted;
    const auto failed_write = [&] {
        const std::vector<fs::path> written = writer.written();
        for (const auto& [path, f] : submitted)
            if (std::find(written.begin(), written.end(), path) == written.end()) return f;
        return submitted.empty() ? -1 : submitted.back().second;
    };
    std::string tile_failure;  // tiles: a write failure on rank 0, reported at the next gather
    int tile_failure_frame = -1;
    frames = dist.pending();

    const bool tty = isatty(fileno(stderr)) != 0 && !o.quiet;
    // On a terminal: a bar redrawn in place ("frame k/n, frames/s, ETA"); otherwise one plain
    // line per frame, which logs and farm schedulers keep.
    std::unique_ptr<Progress> progress;
    if (tty && !frames.empty()) progress = std::make_unique<Progress>(scene_name, int64_t(frames.size()), "frames");
    if (!o.quiet && skipped > 0 && rank0) std::fprintf(stderr, "resume: %d complete frame(s) skipped\n", skipped);
    std::signal(SIGINT, on_interrupt);
    const auto start = std::chrono::steady_clock::now();
    std::vector<double> totals, animate, bake, bvh, visibility, tiles;
    size_t done = 0;
    Frame frame;  // reused: every frame is rendered into the same buffer
    while (const std::optional<int> next = dist.next_frame()) {
        if (g_interrupted) break;
        const int f = *next;
        const fs::path path = pattern.path_for(f);
        if (!farm.claim(path, width, height)) continue;
        render::FrameStats st;
        if (banded) {
            // Rendered band by band and streamed into the file (on rank 0 in tiles mode); the
            // file is created with the first band and published with the last.
            std::optional<output::FrameStream> file;
            const auto encode = [&](const Frame& band) { return output::encode_frame(path, band); };
            const auto write = [&](int b, output::OwnedImage band) {
                if (!file) file.emplace(path, width, height);
                file->write(layout.rows(b).first, std::move(band));
                if (b + 1 == layout.bands()) file->commit();
            };
            const auto render = [&](const render::FrameRenderer::BandFilter& mine, const render::FrameRenderer::BandSink& deliver) {
                farm.simulate(f);
                TraceScope t("frame", "frame", f);
                frame_renderer.render_bands(float(f) / fps, layout, mine, deliver, &st);
            };
            try {
                if (!dist.stream_bands(f, layout, render, encode, write)) continue;
            } catch (const std::exception& e) {
                if (dist.ranks() == 1) throw;
                dist.fail(f, e.what());
                break;
            }
            writer.record_written(path);
        } else {
            std::string failure = std::move(tile_failure);
            tile_failure.clear();
            try {
                farm.simulate(f);
                TraceScope t("frame", "frame", f);
                frame_renderer.render(float(f) / fps, frame, &st);
            } catch (const std::exception& e) {
                if (dist.ranks() == 1) throw;
                if (failure.empty()) failure = e.what();
            }
            if (mode == DistributeMode::tiles) {
                const int reported = tile_failure_frame >= 0 && !failure.empty() ? tile_failure_frame : f;
                tile_failure_frame = -1;
                if (!dist.gather(reported, frame, failure)) continue;
            } else if (!failure.empty()) {
                dist.fail(f, failure);
                break;
            }
            try {
                writer.submit(path, output::encode_frame(path, frame));
                submitted.emplace_back(path, f);
            } catch (const Error& e) {
                if (dist.ranks() == 1) throw;
                if (mode == DistributeMode::tiles) {
                    tile_failure = e.what();
                    tile_failure_frame = failed_write();
                    continue;
                }
                dist.fail(failed_write(), e.what());
                break;
            }
        }
        farm.published(writer.written());
        ++done;
        totals.push_back(st.total_ms);
        animate.push_back(st.animate_ms);
        bake.push_back(st.bake_ms);
        bvh.push_back(st.bvh_ms);
        visibility.push_back(st.visibility_ms);
        tiles.push_back(st.tiles_ms);
        if (o.stats)
            std::fprintf(stderr,
                         "%sframe %d: %.1f ms (animate %.1f, bake %.1f, bvh %.1f, visibility %.1f [vertex %.1f, "
                         "setup+bin %.1f], tiles %.1f [shade, shadows, passes]), %llu triangles, %llu shadowed "
                         "pixels\n",
                         tty ? "\r\033[K" : "", f, st.total_ms, st.animate_ms, st.bake_ms, st.bvh_ms,
                         st.visibility_ms, st.raster.vertex_ms, st.raster.setup_bin_ms, st.tiles_ms,
                         static_cast<unsigned long long>(st.triangles),
                         static_cast<unsigned long long>(st.shadowed_pixels));
        if (progress) {
            progress->update(int64_t(done));
        } else if (!o.quiet) {
            std::fprintf(stderr, "frame %d (%zu/%zu) %.1f ms -> %s\n", f, done, frames.size(), st.total_ms,
                         path.string().c_str());
        }
    }
    try {
        writer.finish();
    } catch (const Error& e) {
        if (dist.ranks() == 1) throw;
        dist.fail(failed_write(), e.what());
    }
    farm.published(writer.written());
    if (progress && !g_interrupted) progress->finish();
    progress.reset();
    if (!dist.finish()) return 1;  // rank 0 reports the failure (finish() throws there)
    if (!o.trace.empty()) {
        trace.deactivate();
        trace.write(o.trace);
    }
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (o.stats && done > 0)
        std::fprintf(stderr,
                     "summary: %zu frames of %dx%d in %.2f s (%.2f fps); median per frame: total %.1f ms, animate %.1f, "
                     "bake %.1f, bvh %.1f, visibility %.1f, tiles %.1f\n",
                     done, width, height, elapsed, double(done) / elapsed, median(totals), median(animate),
                     median(bake), median(bvh), median(visibility), median(tiles));
    if (g_interrupted) {
        std::fprintf(stderr, "tessera: interrupted: %zu frame(s) written; rerun with --resume to continue\n", done);
        return 130;
    }
    if (!o.quiet && farm.held_elsewhere() > 0)
        std::fprintf(stderr, "claim: %d frame(s) claimed by other processes were left to them\n",
                     farm.held_elsewhere());
    if (!o.quiet && !tty)
        std::fprintf(stderr, "rendered %zu frame(s) in %.2f s\n", done, elapsed);
    return 0;
}

// The running binary (for scene directories next to an installed tessera).
std::string executable_path() {
    std::error_code ec;
    const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
    return ec ? std::string() : exe.string();
}

TESSERA_COMMAND(20, [](CLI::App& root) -> Run {
    auto o = std::make_shared<Options>();
    CLI::App* cmd = root.add_subcommand("render", "render animation frames of a scene (built-in name or FILE.json)");
    cmd->add_option("--scene", o->scene, "Scene name (snakes, flag, toon, bumpcube, terrain, metaballs, stress) or FILE.json")
        ->capture_default_str();
    cmd->add_option("--size", o->size, "Frame size WxH, up to 65536 a side; beyond 8192 rendered in bands and streamed (default: the scene's)");
    cmd->add_option("--frames", o->frames, "Frames A:B, inclusive (default: the scene's)");
    cmd->add_option("--fps", o->fps, "Frames per second of scene time (default: the scene's)");
    cmd->add_option("--out", o->out, "Output pattern; #### or %04d is the frame number (.png, .exr, .tif)");
    add_threads_option(*cmd, o->threads);
    cmd->add_option("--renderer", o->renderer, "Visibility by the tile rasterizer or Embree rays")
        ->check(CLI::IsMember({"raster", "raytrace"}))
        ->capture_default_str();
    cmd->add_option("--shadows", o->shadows, "Shadows: none, map or rays (default: the scene's)")
        ->check(CLI::IsMember({"none", "map", "rays"}));
    cmd->add_option("--png", o->png,
                    "PNG compression: fast (Paeth filter, zlib run-length; for animation work) or small "
                    "(adaptive filters, zlib level 9; slower, smaller files)")
        ->check(CLI::IsMember({"fast", "small"}))
        ->capture_default_str();
    cmd->add_flag("--resume", o->resume, "Skip frames whose files are already complete");
    cmd->add_option("--shard", o->shard, "Render shard I of N (every N-th frame from the I-th, 0-based)")
        ->capture_default_str();
    cmd->add_flag("--stats", o->stats, "Print per-stage times per frame and a summary");
    cmd->add_option("--trace", o->trace, "Write a Chrome trace event JSON (Perfetto, chrome://tracing)");
    cmd->add_flag("--quiet", o->quiet, "No progress output");
    add_farm_options(*cmd, o->farm);
    return [o] { return run(*o, executable_path()); };
});

}  // namespace
}  // namespace tessera::cli
