// `tessera render`: animation frames of a scene file.
//   tessera render --scene NAME|FILE.json [--size WxH] [--frames A:B] [--fps F]
//                  [--out out/NAME_####.png|.exr|.tif] [--threads N]
//                  [--renderer raster|raytrace] [--shadows none|map|rays] [--samples 1|4|8|16]
//                  [--png fast|small] [--exr zip|piz|dwaa|none] [--resume] [--shard I/N] [--stats]
//                  [--trace FILE.json]
//                  [--quiet]
// Frames are encoded and written on a background thread (FrameWriter) while the next one
// renders, each atomically (temp name + rename), so an interrupted run leaves only complete
// frames and --resume skips them. Frames beyond one 8192x8192 pass are rendered band by band
// and streamed into their file (FrameRenderer::render_bands, FrameStream), so memory holds a
// band, not the frame. Ctrl-C, SIGTERM or SIGHUP finishes the frame in hand, waits for the
// writer and exits 128 + the signal's number (130, 143, 129). Everything the flags and the
// scene say is checked before the first frame: every frame's camera, the output folders, the
// trace file. Exit codes as every command: 2 for bad flags, 1 for a failed run.
#include <unistd.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstring>
#include <cstdio>
#include <filesystem>
#include <map>
#include <new>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "examples/command.h"
#include "examples/distribute.h"
#include "examples/farm/frame_claim.h"
#include "examples/frame_sequence.h"
#include "examples/progress.h"
#include "examples/render_farm.h"
#include "examples/resident_memory.h"
#include "examples/shadow_map_flags.h"
#include "examples/signals.h"
#include "raster/asset/framing.h"
#include "raster/core/atomic_file.h"
#include "raster/core/error.h"
#include "raster/core/trace.h"
#include "raster/io/camera_file.h"
#include "raster/io/image_completeness.h"
#include "raster/io/image_io.h"
#include "raster/output/frame_encoding.h"
#include "raster/output/frame_stream.h"
#include "raster/output/frame_writer.h"
#include "raster/render/frame_renderer.h"
#include "raster/scene_file/scene_build.h"
#include "raster/scene_file/scene_file_error.h"
#include "raster/scene_file/scene_library.h"
#include "raster/scene_file/scene_parse.h"

namespace tessera::cli {
namespace {

namespace fs = std::filesystem;

// Frames up to 8K (and anything within one 8192 x 8192 viewport) are rendered whole in memory
// and written by the background FrameWriter; larger ones are rendered band by band and
// streamed into the file (band_layout.h, image_stream.h), up to this size per side.
constexpr int kMaxSide = 65536;

struct Options {
    std::string scene = "snakes";
    std::string size, frames, renderer = "raster", shadows, shard = "0/1", png = "fast", exr = "zip";
    std::optional<std::string> out, trace, fps;  // given (perhaps empty) or not
    int threads = 0;
    int samples = 0;  // 0: the scene's
    bool resume = false, stats = false, quiet = false;
    FarmOptions farm;  // --claim, --checkpoint-every, --distribute (render_farm.h)
    ShadowMapFlags map_flags;  // over every light's "shadow_map"
};

// The folders of `frames` (one for all, or one per frame when the pattern's placeholder is
// in a folder's name, "out/####/beauty.png"), made before any rendering: a folder that
// cannot be made or cannot take files fails the run now, not after frames were written.
void prepare_output_folders(const FramePattern& pattern, const std::vector<int>& frames) {
    std::set<fs::path> folders;
    for (const int f : frames) {
        const fs::path file = pattern.path_for(f);
        folders.insert(file.parent_path().empty() ? fs::path(".") : file.parent_path());
    }
    // All checked before any is made: a file in the way of the last one leaves no folders.
    for (const fs::path& dir : folders) {
        fs::path existing = dir;  // the nearest part of it that exists ("out" of "out/a/b": ".")
        std::error_code ec;
        while (!fs::exists(existing, ec) && existing != existing.parent_path())
            existing = existing.has_parent_path() ? existing.parent_path() : fs::path(".");
        if (fs::exists(existing, ec) && !fs::is_directory(existing, ec))
            throw Error("cannot write frames to '" + dir.string() + "': '" + existing.string() + "' is not a directory");
        if (access(existing.c_str(), W_OK) != 0)
            throw Error("cannot write frames to '" + dir.string() + "': permission denied");
    }
    for (const fs::path& dir : folders) {
        std::error_code ec;
        fs::create_directories(dir, ec);
        if (!fs::is_directory(dir))
            throw Error("cannot write frames to '" + dir.string() + "': " + (ec ? ec.message() : "not a directory"));
    }
}

// --fps: a positive, finite number (no silent fallback to the scene's for 0, -5 or nan).
float parse_fps(const std::string& text) {
    float fps = 0.0f;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), fps);
    if (ec != std::errc() || end != text.data() + text.size() || !(fps > 0.0f) || !std::isfinite(fps))
        throw UsageError("--fps expects a positive number of frames per second, got '" + text + "'");
    return fps;
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

// The scene file named by --scene, read and checked (its warnings printed).
struct LoadedScene {
    fs::path file;
    std::string name;  // the file's stem: names the default output and the progress line
    scene_file::SceneSpec spec;
};

LoadedScene load_scene(const std::string& scene, const std::string& executable) {
    LoadedScene loaded;
    loaded.file = scene_file::find_scene(scene, scene_file::scene_directories(TESSERA_SCENE_DIR, executable));
    std::vector<std::string> warnings;
    loaded.spec = scene_file::load_scene_file(loaded.file, warnings);
    for (const std::string& w : warnings) std::fprintf(stderr, "tessera: warning: %s\n", w.c_str());
    loaded.name = loaded.file.stem().string();
    return loaded;
}

// What the run renders: the flags over the scene's defaults, all checked before any work.
struct RenderPlan {
    int width = 0, height = 0;
    FrameRange range;
    Shard shard;
    float fps = 0.0f;
    FramePattern pattern{""};
    render::RendererKind renderer{};
    render::ShadowMode shadows{};
    int samples = 1;
    DistributeMode mode{};
};

// Every frame's camera, checked before the first frame is rendered: keyframes and an orbit
// can bring the eye onto the lookat point, or the view along 'up', at a single frame.
void check_cameras(const LoadedScene& scene, const RenderPlan& plan) {
    for (const int f : frames_of_shard(plan.range, plan.shard)) {
        const float time = float(f) / plan.fps;  // as FrameLoop renders it
        try {
            io::validate_camera(render::camera_at(scene.spec.camera, time, float(plan.width) / float(plan.height)));
        } catch (const std::invalid_argument& e) {
            char when[64];
            std::snprintf(when, sizeof when, "at frame %d (%.3g s): ", f, double(time));
            throw scene_file::SceneFileError(scene.file.string() + ": /camera: " + when + e.what());
        }
    }
}

RenderPlan plan_render(const Options& o, const LoadedScene& scene) {
    const scene_file::SceneSpec& spec = scene.spec;
    RenderPlan plan;
    plan.width = spec.size.x, plan.height = spec.size.y;
    if (!o.size.empty()) parse_size(o.size, "--size", plan.width, plan.height);
    if (plan.width > kMaxSide || plan.height > kMaxSide)
        throw UsageError("--size " + std::to_string(plan.width) + "x" + std::to_string(plan.height) + ": at most " +
                         std::to_string(kMaxSide) + " pixels per side");
    plan.range = FrameRange{spec.animation.first, spec.animation.last};
    if (!o.frames.empty()) plan.range = parse_frame_range(o.frames);
    plan.shard = parse_shard(o.shard);
    plan.fps = o.fps ? parse_fps(*o.fps) : spec.animation.fps;
    if (o.out && o.out->empty()) throw UsageError("--out: expected an output pattern, got ''");
    plan.pattern = FramePattern(o.out ? *o.out : "out/" + scene.name + "_####.png");
    const FramePattern& pattern = plan.pattern;
    if (!pattern.has_placeholder() && plan.range.count() > 1)
        throw UsageError("--out '" + pattern.text() + "' has no #### or %04d, but " + std::to_string(plan.range.count()) +
                         " frames would overwrite it");
    if (pattern.path_for(plan.range.first).filename().empty() || pattern.text().back() == '/')
        throw UsageError("--out '" + pattern.text() + "': no file name (use e.g. DIR/frame_####.png)");
    if (!output::frame_format_supported(pattern.path_for(plan.range.first)))
        throw UsageError("--out '" + pattern.text() + "': no image format for that extension (use .png, .exr or .tif)");
    if (o.trace) {  // checked now, not after the frames are rendered
        if (o.trace->empty()) throw UsageError("--trace: expected a file name, got ''");
        check_writable(*o.trace);
    }
    plan.renderer = render::parse_renderer(o.renderer);
    plan.shadows = render::parse_shadow_mode(o.shadows.empty() ? spec.shadows : o.shadows);
    plan.samples = o.samples ? o.samples : spec.samples;
    if (plan.shadows != render::ShadowMode::none && spec.lights.size() > 4) {  // light masks hold 4 lights
        const std::string why = "at most 4 lights cast shadows, the scene has " + std::to_string(spec.lights.size());
        if (!o.shadows.empty()) throw UsageError("--shadows " + o.shadows + ": " + why);
        throw scene_file::SceneFileError(scene.file.string() + ": /lights: " + why + " and /render/shadows is '" +
                                         spec.shadows + "'");
    }
    check_cameras(scene, plan);
    plan.mode = parse_distribute(o.farm.distribute);
    if (plan.mode == DistributeMode::tiles && o.farm.claim)
        throw UsageError("--claim works on whole frames: not with --distribute tiles");
    return plan;
}

// This shard's frames still to render: with --resume, complete frames are skipped (and the
// temporaries a killed run left beside the others removed).
struct PendingFrames {
    std::vector<int> frames;
    int skipped = 0;
};

PendingFrames pending_frames(const Options& o, const RenderPlan& plan) {
    PendingFrames pending;
    const std::vector<int> shard_frames = frames_of_shard(plan.range, plan.shard);
    if (o.resume && !o.farm.claim) {  // with --claim, a frame's temporaries go when its claim is won
        std::vector<fs::path> paths;
        for (int f : shard_frames) paths.push_back(plan.pattern.path_for(f));
        remove_stale_temporaries(paths);
    }
    for (int f : shard_frames) {
        const fs::path path = plan.pattern.path_for(f);
        if (!(o.resume && io::image_is_complete(path, plan.width, plan.height))) {
            pending.frames.push_back(f);
            continue;
        }
        ++pending.skipped;
        // A process killed between publishing a frame and removing its claim leaves the claim
        // behind: break it by the usual protocol (stale owners only) and hand it straight back.
        if (o.farm.claim &&
            farm::try_claim(path, {true, o.farm.claim_timeout}) != farm::ClaimResult::held)
            farm::release_claim(path);
    }
    return pending;
}

// "shade 1.0, background 0.1, ..., of tiles 2.0 thread ms": the tile stage's passes
// (render/tile_pass_times.h), `ms(p)` for pass p, whole tiles `tiles`.
template <class PassMs>
std::string tile_pass_list(const PassMs& ms, double tiles) {
    std::string out;
    char item[64];
    for (size_t p = 0; p < render::kTilePasses; ++p) {
        std::snprintf(item, sizeof item, "%s %.1f, ", std::string(render::tile_pass_name(render::TilePass(p))).c_str(), ms(p));
        out += item;
    }
    std::snprintf(item, sizeof item, "of tiles %.1f thread ms", tiles);
    return out + item;
}

// Per-stage times of the frames rendered, for --stats and its summary.
struct StageTimes {
    std::vector<double> total, animate, bake, bvh, shadow_maps, visibility, tiles;
    std::array<std::vector<double>, render::kTilePasses + 1> tile_passes;  // and whole tiles, last

    void add(const render::FrameStats& st) {
        for (size_t p = 0; p < render::kTilePasses; ++p) tile_passes[p].push_back(st.tile_passes.ms[p]);
        tile_passes.back().push_back(st.tile_passes.tiles_ms);
        total.push_back(st.total_ms);
        animate.push_back(st.animate_ms);
        bake.push_back(st.bake_ms);
        bvh.push_back(st.bvh_ms);
        shadow_maps.push_back(st.shadow_maps_ms);
        visibility.push_back(st.visibility_ms);
        tiles.push_back(st.tiles_ms);
    }
};

// The frame loop of one process: renders the frames the distribution hands it, in memory or
// band by band, writes them through the background writer, reports progress and failures.
class FrameLoop {
public:
    FrameLoop(const Options& o, const LoadedScene& scene, const RenderPlan& plan, std::vector<int> frames);
    // Renders every frame; returns the exit code.
    int run(int skipped);

private:
    enum class Outcome { rendered, skipped, stop };
    Outcome render_in_bands(int f, const fs::path& path, render::FrameStats& st);
    Outcome render_in_memory(int f, const fs::path& path, render::FrameStats& st);
    void report(int f, const fs::path& path, const render::FrameStats& st);
    // `stopped_by`: the signal that stopped the loop, or 0.
    int finish(int stopped_by);
    // A failed write names the first frame not yet on disk.
    int failed_write() const;

    const Options& o_;
    const LoadedScene& loaded_;
    const RenderPlan& plan_;
    const std::unique_ptr<Distribution> distribution_;
    Distribution& dist_;
    Trace trace_;
    render::AnimatedScene scene_;
    render::FrameRenderer frame_renderer_;
    output::FrameWriter writer_;
    FarmRun farm_;
    const bool banded_;
    const render::BandLayout layout_;
    // Distributed: a failure is handed to rank 0 (which names the rank and the frame) instead
    // of ending this rank alone.
    std::vector<std::pair<fs::path, int>> submitted_;
    std::string tile_failure_;  // tiles: a write failure on rank 0, reported at the next gather
    int tile_failure_frame_ = -1;
    Frame frame_;  // reused: every frame is rendered into the same buffer
    std::vector<int> frames_;  // this rank's share, as the distribution sees it
    const bool tty_;
    std::unique_ptr<Progress> progress_;
    std::chrono::steady_clock::time_point start_;
    StageTimes times_;
    size_t done_ = 0;
};

FrameLoop::FrameLoop(const Options& o, const LoadedScene& scene, const RenderPlan& plan, std::vector<int> frames)
    : o_(o),
      loaded_(scene),
      plan_(plan),
      distribution_(make_distribution(plan.mode, std::move(frames))),
      dist_(*distribution_),
      scene_([&] {
          if (o.trace) trace_.activate();
          TraceScope t("build scene");
          std::vector<std::string> warnings;
          render::AnimatedScene built = scene_file::build_scene(scene.spec, &warnings);
          o.map_flags.apply(built.scene.lights);
          if (dist_.rank() == 0) {
              for (const std::string& w : warnings) std::fprintf(stderr, "tessera: warning: %s\n", w.c_str());
              if (!scene.spec.camera_given)
                  std::fprintf(stderr, "tessera: camera (framed): %s\n", asset::camera_flags(built.camera.camera).c_str());
          }
          return built;
      }()),
      frame_renderer_(scene_, plan.width, plan.height, plan.renderer, plan.shadows, plan.samples),
      writer_(2, output::FileSettings{output::parse_png_compression(o.png), output::parse_exr_compression(o.exr)}),
      farm_(o.farm, o.resume, scene_, scene.spec.textures, scene.name, plan.pattern.fixed_directory()),
      banded_(render::needs_bands(plan.width, plan.height)),
      layout_(render::band_layout(plan.width, plan.height)),
      frames_(dist_.pending()),
      tty_(isatty(fileno(stderr)) != 0 && !o.quiet) {
    if (!banded_) {
        const auto [rows_first, rows_last] = dist_.rows(plan.height);
        frame_renderer_.set_rows(rows_first, rows_last);
    }
}

int FrameLoop::failed_write() const {
    const std::vector<fs::path> written = writer_.written();
    for (const auto& [path, f] : submitted_)
        if (std::find(written.begin(), written.end(), path) == written.end()) return f;
    return submitted_.empty() ? -1 : submitted_.back().second;
}

int FrameLoop::run(int skipped) {
    // On a terminal: a bar redrawn in place ("frame k/n, frames/s, ETA"); otherwise one plain
    // line per frame, which logs and farm schedulers keep.
    if (tty_ && !frames_.empty())
        progress_ = std::make_unique<Progress>(loaded_.name, int64_t(frames_.size()), "frames");
    if (!o_.quiet && skipped > 0 && dist_.rank() == 0)
        std::fprintf(stderr, "resume: %d complete frame(s) skipped\n", skipped);
    // SIGINT, SIGTERM, SIGHUP: finish the frame in hand, then stop (signals.h).
    const StopRequest stop;
    start_ = std::chrono::steady_clock::now();
    while (const std::optional<int> next = dist_.next_frame()) {
        if (stop.signal()) break;
        const int f = *next;
        const fs::path path = plan_.pattern.path_for(f);
        if (!farm_.claim(path, plan_.width, plan_.height)) continue;
        render::FrameStats st;
        Outcome outcome;
        try {
            outcome = banded_ ? render_in_bands(f, path, st) : render_in_memory(f, path, st);
        } catch (const std::bad_alloc&) {
            // Only a large frame makes --size the thing to change (a band holds ~4 M pixels).
            const bool large = int64_t(plan_.width) * plan_.height > (int64_t(1) << 22);
            throw Error("out of memory rendering frame " + std::to_string(f) + " (" + std::to_string(plan_.width) +
                        "x" + std::to_string(plan_.height) + ")" + (large ? ": try a smaller --size" : ""));
        }
        if (outcome == Outcome::skipped) continue;
        if (outcome == Outcome::stop) break;
        report(f, path, st);
    }
    return finish(stop.signal());
}

// Rendered band by band and streamed into the file (on rank 0 in tiles mode); the file is
// created with the first band and published with the last.
FrameLoop::Outcome FrameLoop::render_in_bands(int f, const fs::path& path, render::FrameStats& st) {
    std::optional<output::FrameStream> file;
    const auto encode = [&](const Frame& band) { return output::encode_frame(path, band); };
    const auto write = [&](int b, output::OwnedImage band) {
        if (!file)
            file.emplace(path, plan_.width, plan_.height,
                         output::FileSettings{output::parse_png_compression(o_.png), output::parse_exr_compression(o_.exr)});
        file->write(layout_.rows(b).first, std::move(band));
        if (b + 1 == layout_.bands()) file->commit();
    };
    const auto render = [&](const render::FrameRenderer::BandFilter& mine,
                            const render::FrameRenderer::BandSink& deliver) {
        farm_.simulate(f);
        TraceScope t("frame", "frame", f);
        frame_renderer_.render_bands(float(f) / plan_.fps, layout_, mine, deliver, &st);
    };
    try {
        if (!dist_.stream_bands(f, layout_, render, encode, write)) return Outcome::skipped;
    } catch (const std::exception& e) {
        if (dist_.ranks() == 1) throw;
        dist_.fail(f, e.what());
        return Outcome::stop;
    }
    writer_.record_written(path);
    return Outcome::rendered;
}

// Rendered whole in memory (gathered to rank 0 in tiles mode) and handed to the background
// writer.
FrameLoop::Outcome FrameLoop::render_in_memory(int f, const fs::path& path, render::FrameStats& st) {
    Frame& frame = frame_;
    std::string failure = std::move(tile_failure_);
    tile_failure_.clear();
    // 8-bit files of whole frames (not gathered from ranks as floats): encoded tile by tile
    // by the renderer, into a buffer the writer has finished with.
    const bool direct_8bit =
        output::frame_pixel_type(path) == io::PixelType::u8 && plan_.mode != DistributeMode::tiles;
    std::vector<uint8_t> bytes;
    size_t non_finite = 0;
    try {
        farm_.simulate(f);
        TraceScope t("frame", "frame", f);
        if (direct_8bit) {
            bytes = writer_.spare_bytes();
            non_finite = frame_renderer_.render_srgb8(float(f) / plan_.fps, bytes, &st);
        } else {
            frame_renderer_.render(float(f) / plan_.fps, frame, &st);
        }
    } catch (const std::exception& e) {
        if (dist_.ranks() == 1) throw;
        if (failure.empty()) failure = e.what();
    }
    if (plan_.mode == DistributeMode::tiles) {
        const int reported = tile_failure_frame_ >= 0 && !failure.empty() ? tile_failure_frame_ : f;
        tile_failure_frame_ = -1;
        if (!dist_.gather(reported, frame, failure)) return Outcome::skipped;
    } else if (!failure.empty()) {
        dist_.fail(f, failure);
        return Outcome::stop;
    }
    try {
        if (direct_8bit) {
            if (non_finite > 0) throw output::non_finite_frame_error(path, non_finite);
            writer_.submit(path, output::OwnedImage{plan_.width, plan_.height, 4, io::PixelType::u8, std::move(bytes)});
        } else {
            writer_.submit(path, output::encode_frame(path, frame, writer_.spare_bytes()));
        }
        submitted_.emplace_back(path, f);
    } catch (const Error& e) {
        if (dist_.ranks() == 1) throw;
        if (plan_.mode == DistributeMode::tiles) {
            tile_failure_ = e.what();
            tile_failure_frame_ = failed_write();
            return Outcome::skipped;
        }
        dist_.fail(failed_write(), e.what());
        return Outcome::stop;
    }
    return Outcome::rendered;
}

void FrameLoop::report(int f, const fs::path& path, const render::FrameStats& st) {
    farm_.published(writer_.written());
    ++done_;
    times_.add(st);
    if (o_.stats)
        std::fprintf(stderr,
                     "%sframe %d: %.1f ms (animate %.1f, bake %.1f, bvh %.1f [%llu/%llu objects built], shadow maps %.1f "
                     "[%llu/%llu cascades drawn], "
                     "visibility %.1f "
                     "[vertex %.1f, setup+bin %.1f], tiles %.1f [%s]), %llu triangles, %llu shadowed "
                     "pixels, heap %.1f MiB, rss %.1f MiB\n",
                     tty_ ? "\r\033[K" : "", f, st.total_ms, st.animate_ms, st.bake_ms, st.bvh_ms,
                     static_cast<unsigned long long>(st.bvh_objects_built),
                     static_cast<unsigned long long>(st.bvh_objects), st.shadow_maps_ms,
                     static_cast<unsigned long long>(st.shadow_cascades_drawn),
                     static_cast<unsigned long long>(st.shadow_cascades), st.visibility_ms,
                     st.raster.vertex_ms,
                     st.raster.setup_bin_ms, st.tiles_ms,
                     tile_pass_list([&](size_t p) { return st.tile_passes.ms[p]; }, st.tile_passes.tiles_ms).c_str(),
                     static_cast<unsigned long long>(st.triangles),
                     static_cast<unsigned long long>(st.shadowed_pixels), heap_mib(), resident_mib());
    if (progress_) {
        progress_->update(int64_t(done_));
    } else if (!o_.quiet) {
        std::fprintf(stderr, "frame %d (%zu/%zu) %.1f ms -> %s\n", f, done_, frames_.size(), st.total_ms,
                     path.string().c_str());
    }
}

// Waits for the writer and the other ranks, writes the trace, prints the summary.
int FrameLoop::finish(int stopped_by) {
    try {
        writer_.finish();
    } catch (const Error& e) {
        if (dist_.ranks() == 1) throw;
        dist_.fail(failed_write(), e.what());
    }
    farm_.published(writer_.written());
    if (progress_ && !stopped_by) progress_->finish();
    progress_.reset();
    if (!dist_.finish()) return 1;  // rank 0 reports the failure (finish() throws there)
    if (o_.trace) {
        trace_.deactivate();
        trace_.write(*o_.trace);
    }
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    if (o_.stats && done_ > 0)
        std::fprintf(stderr,
                     "summary: %zu frames of %dx%d in %.2f s (%.2f fps); median per frame: total %.1f ms, animate %.1f, "
                     "bake %.1f, bvh %.1f, shadow maps %.1f, visibility %.1f, tiles %.1f [%s]; peak rss %.1f MiB\n",
                     done_, plan_.width, plan_.height, elapsed, double(done_) / elapsed, median(times_.total),
                     median(times_.animate), median(times_.bake), median(times_.bvh), median(times_.shadow_maps),
                     median(times_.visibility),
                     median(times_.tiles),
                     tile_pass_list([&](size_t p) { return median(times_.tile_passes[p]); },
                                    median(times_.tile_passes.back())).c_str(),
                     peak_resident_mib());
    if (stopped_by) {
        std::fprintf(stderr, "tessera: interrupted by %s: %zu frame(s) written; rerun with --resume to continue\n",
                     signal_name(stopped_by).c_str(), done_);
        return 128 + stopped_by;  // as the shell reports a process the signal ended
    }
    if (!o_.quiet && farm_.held_elsewhere() > 0)
        std::fprintf(stderr, "claim: %d frame(s) claimed by other processes were left to them\n",
                     farm_.held_elsewhere());
    if (!o_.quiet && !tty_) std::fprintf(stderr, "rendered %zu frame(s) in %.2f s\n", done_, elapsed);
    return 0;
}

// The command: the scene, the plan, the frames still to render, then the frame loop.
int run(const Options& o, const std::string& executable) {
    const auto guard = limit_threads(o.threads);
    const LoadedScene scene = load_scene(o.scene, executable);
    const RenderPlan plan = plan_render(o, scene);
    PendingFrames pending = pending_frames(o, plan);
    prepare_output_folders(plan.pattern, pending.frames);
    std::optional<FrameLoop> loop;
    try {
        loop.emplace(o, scene, plan, std::move(pending.frames));
    } catch (const std::bad_alloc&) {
        throw Error("out of memory building the scene of '" + scene.file.string() +
                    "' (its meshes, textures and tessellations need more than this machine has free)");
    }
    return loop->run(pending.skipped);
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
    add_samples_option(*cmd, o->samples, "(default: the scene's, else 1)");
    add_shadow_map_options(*cmd, o->map_flags);
    cmd->add_option("--png", o->png,
                    "PNG compression: fast (Paeth filter, zlib run-length; for animation work) or small "
                    "(adaptive filters, zlib level 9; slower, smaller files)")
        ->check(CLI::IsMember({"fast", "small"}))
        ->capture_default_str();
    cmd->add_option("--exr", o->exr,
                    "EXR compression: zip (lossless), piz (lossless, smaller on textured frames, slower), dwaa "
                    "(lossy colour, smallest) or none")
        ->check(CLI::IsMember({"zip", "piz", "dwaa", "none"}))
        ->capture_default_str();
    cmd->add_flag("--resume", o->resume, "Skip frames whose files are already complete");
    cmd->add_option("--shard", o->shard, "Render shard I of N (every N-th frame from the I-th, 0-based)")
        ->capture_default_str();
    cmd->add_flag("--stats", o->stats, "Print per-stage times and memory (heap, resident) per frame, and a summary");
    cmd->add_option("--trace", o->trace, "Write a Chrome trace event JSON (Perfetto, chrome://tracing)");
    cmd->add_flag("--quiet", o->quiet, "No progress output");
    add_farm_options(*cmd, o->farm);
    return [o] { return run(*o, executable_path()); };
});

}  // namespace
}  // namespace tessera::cli
