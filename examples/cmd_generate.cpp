// `tessera generate rd | heightfield | normalmap`: the procedural generators as image files.
//   tessera generate rd --preset NAME --size WxH --steps N [--seed S] [--threads N] --out FILE
//   tessera generate rd ... --frames N --out 'rd_####.png'  (the growth as an animation)
//   tessera generate rd --list-presets
//   tessera generate heightfield --size WxH [--seed S] [--octaves K] [--threads N] --out FILE
//                                [--relief fbm|ridged|warped|dunes] [--cells C] [--erode N]
//   tessera generate normalmap --in HEIGHT --out FILE
// Every file is written atomically (raster/image_io.h), so a failed or interrupted run leaves
// nothing behind; every bad value is rejected before any work starts.
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "examples/command.h"
#include "examples/frame_sequence.h"
#include "examples/progress.h"
#include "procedural/erosion.h"
#include "procedural/heightfield.h"
#include "procedural/normal_map.h"
#include "procedural/rd_color.h"
#include "procedural/rd_initial.h"
#include "procedural/rd_presets.h"
#include "procedural/reaction_diffusion.h"
#include "raster/core/atomic_file.h"
#include "raster/core/error.h"
#include "raster/io/image_io.h"

namespace tessera::cli {
namespace {

namespace tp = tessera::procedural;
namespace fs = std::filesystem;

struct Options {
    // rd
    std::string preset = "spots";
    std::string size;
    int steps = -1;
    int frames = 1;
    uint32_t seed = 1;
    int threads = 0;
    std::string out;
    bool list_presets = false;
    float feed = 0.0f, kill = 0.0f, dt = 1.0f, anisotropy = 0.0f;
    bool feed_given = false, kill_given = false;  // override the preset's rates
    std::string boundary = "periodic";
    std::string init = "spots";
    std::string init_image;
    // heightfield
    int octaves = 8;
    int cells = 4;
    float gain = 0.5f;
    std::string relief = "fbm";
    bool no_tile = false;
    int erode = 0;
    // normalmap
    std::string in;
    float strength = 16.0f;
    bool wrap = false;
};

std::string lower_extension(const fs::path& path) {
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return ext;
}

// Formats that store floats: heights and normals keep full precision there.
bool float_format(const fs::path& path) {
    const std::string ext = lower_extension(path);
    return ext == ".exr" || ext == ".tif" || ext == ".tiff" || ext == ".hdr";
}

// Before the work: a missing folder is found now, not after an hour of simulation.
void check_output(const std::string& out) {
    if (out.empty()) throw UsageError("--out FILE is required");
    if (!io::image_format_supported(out))
        throw UsageError("cannot write '" + out + "': no image format for extension '" +
                         fs::path(out).extension().string() + "' (use .png, .exr or .tif)");
    check_writable(FramePattern(out).path_for(0));  // a frame pattern's folder, or the file's
}

// Refuses sizes whose working set exceeds the machine's memory, before allocating anything.
void check_memory(int width, int height, double bytes_per_cell, const char* what) {
    tp::check_grid_size(width, height, what);
    const double need = double(width) * double(height) * bytes_per_cell;
    const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGE_SIZE);
    const double have = pages > 0 && page > 0 ? double(pages) * double(page) : 0.0;
    if (have > 0 && need > 0.8 * have) {
        char text[256];
        std::snprintf(text, sizeof text, "--size %dx%d needs %.1f GiB for the %s, more than 80%% of this machine's %.1f GiB",
                      width, height, need / (1 << 30), what, have / (1 << 30));
        throw UsageError(text);
    }
}

void require_finite(float value, const char* flag) {
    if (!std::isfinite(value)) throw UsageError(std::string(flag) + " must be a finite number");
}

int list_presets() {
    std::printf("%-10s %-8s %-8s %s\n", "preset", "feed", "kill", "pattern");
    for (const tp::RdPreset& p : tp::rd_presets())
        std::printf("%-10.*s %-8.4f %-8.4f %.*s\n", int(p.name.size()), p.name.data(), p.feed,
                    p.kill, int(p.pattern.size()), p.pattern.data());
    return 0;
}

tp::Grid image_to_grid(const io::FloatImage& image) {
    tp::Grid g(image.width, image.height);
    const int colour = std::min(image.channels, 3);  // ignore alpha
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            float sum = 0;
            for (int c = 0; c < colour; ++c) sum += image.at(x, y, c);
            g.at(x, y) = sum / float(colour);
        }
    return g;
}

int run_rd(const Options& o) {
    if (o.list_presets) return list_presets();
    const tp::RdPreset* preset = tp::find_rd_preset(o.preset);
    if (!preset)
        throw UsageError("unknown preset '" + o.preset + "'; valid presets: " + tp::rd_preset_names());
    if (o.size.empty()) throw UsageError("--size WxH is required");
    if (o.steps < 0) throw UsageError("--steps N is required");
    int width = 0, height = 0;
    parse_size(o.size, "--size", width, height);
    check_output(o.out);
    // Frame files follow the render command's patterns ("rd_####.png" or "rd_%04d.png").
    const FramePattern pattern(o.out);
    if (o.frames > 1 && !pattern.has_placeholder())
        throw UsageError("--frames " + std::to_string(o.frames) + " needs a frame number placeholder in --out "
                         "(#### or %04d), got '" + o.out + "'");
    // Two states of two float grids, the colour image, and an optional seed image.
    check_memory(width, height, 4 * 4 + 3 + (o.init_image.empty() ? 0 : 16), "reaction-diffusion state");

    tp::GrayScott params;
    if (o.feed_given) require_finite(o.feed, "--feed");
    if (o.kill_given) require_finite(o.kill, "--kill");
    params.feed = o.feed_given ? o.feed : preset->feed;
    params.kill = o.kill_given ? o.kill : preset->kill;
    require_finite(o.dt, "--dt");
    require_finite(o.anisotropy, "--anisotropy");
    params.dt = o.dt;
    params.anisotropy = o.anisotropy;
    params.boundary = o.boundary == "clamped" ? tp::Boundary::clamped : tp::Boundary::periodic;
    if (params.anisotropy >= -1.0f && params.anisotropy <= 1.0f && params.dt > tp::max_stable_dt(params)) {
        std::fprintf(stderr,
                     "tessera: warning: --dt %g is unstable (explicit Euler diffusion needs "
                     "Da*dt*%.2f <= 2); using dt=%g\n",
                     double(params.dt), double(tp::laplacian_spectral_radius(params.anisotropy)),
                     double(tp::max_stable_dt(params)));
        params.dt = tp::max_stable_dt(params);
    }
    tp::validate(params, width, height);

    tp::RdState initial;
    if (o.init == "image") {
        if (o.init_image.empty()) throw UsageError("--init image needs --init-image FILE");
        tp::Grid image = image_to_grid(io::read_image(o.init_image));
        if (image.width != width || image.height != height)
            throw UsageError("--init-image is " + std::to_string(image.width) + "x" +
                             std::to_string(image.height) + ", --size is " + o.size);
        initial = tp::rd_initial_image(image);
    } else if (o.init == "noise") {
        initial = tp::rd_initial_noise(width, height, o.seed);
    } else {
        initial = tp::rd_initial_spots(width, height, o.seed);
    }

    const auto limit = limit_threads(o.threads);
    tp::ReactionDiffusion rd(params, std::move(initial));
    Progress progress("rd " + o.preset, o.steps, "steps");
    const int chunk = std::max(1, o.steps / 200);
    int done = 0;
    // Frame f of F shows the pattern after steps * f / F steps (the last one after all of them).
    for (int frame = 1; frame <= o.frames; ++frame) {
        const int target = int(int64_t(o.steps) * frame / o.frames);
        while (done < target) {
            const int n = std::min(chunk, target - done);
            rd.step(n);
            done += n;
            progress.update(done);
        }
        const std::vector<uint8_t> rgb = tp::rd_colorize(rd.state());
        const fs::path file = o.frames > 1 ? pattern.path_for(frame) : fs::path(o.out);
        io::write_image(file, {width, height, 3, io::PixelType::u8, rgb.data(), /*srgb=*/true});
    }
    progress.finish();
    return 0;
}

int run_heightfield(const Options& o) {
    if (o.size.empty()) throw UsageError("--size WxH is required");
    int width = 0, height = 0;
    parse_size(o.size, "--size", width, height);
    check_output(o.out);
    check_memory(width, height, 3 * 4 + 4, "heightfield");
    tp::HeightfieldParams params;
    if (o.relief == "ridged") params.relief = tp::Relief::ridged;
    else if (o.relief == "warped") params.relief = tp::Relief::warped;
    else if (o.relief == "dunes") params.relief = tp::Relief::dunes;
    params.fractal = {o.octaves, 2.0f, o.gain, o.seed};
    params.cells = o.cells;
    params.tileable = !o.no_tile;
    params.dunes.seed = o.seed;
    params.dunes.wind = glm::vec2(0.8f, 0.6f);
    require_finite(o.gain, "--gain");

    const auto limit = limit_threads(o.threads);
    tp::Grid heights = tp::generate_heightfield(width, height, params);
    if (o.erode > 0) {
        tp::ThermalErosion erosion;
        erosion.iterations = o.erode;
        erosion.boundary = params.tileable ? tp::Boundary::periodic : tp::Boundary::clamped;
        tp::erode_thermal(heights, erosion);
    }
    if (float_format(o.out)) {
        io::write_image(o.out, {width, height, 1, io::PixelType::f32, heights.values.data()});
    } else {
        // 16-bit integer formats (PNG): quantise [0, 1] to the full 0..65535 range.
        std::vector<uint16_t> q(heights.size());
        for (size_t i = 0; i < q.size(); ++i)
            q[i] = uint16_t(std::lround(std::clamp(heights.values[i], 0.0f, 1.0f) * 65535.0f));
        io::write_image(o.out, {width, height, 1, io::PixelType::u16, q.data()});
    }
    return 0;
}

int run_normalmap(const Options& o) {
    if (o.in.empty()) throw UsageError("--in HEIGHT is required");
    check_output(o.out);
    require_finite(o.strength, "--strength");
    const io::FloatImage image = io::read_image(o.in);
    check_memory(image.width, image.height, 12 + 4, "normal map");
    const tp::Grid heights = image_to_grid(image);
    for (float v : heights.values)
        if (!std::isfinite(v)) throw Error("height map '" + o.in + "' holds non-finite values");
    const tp::NormalMap normals =
        tp::normal_map(heights, o.strength, o.wrap ? tp::Boundary::periodic : tp::Boundary::clamped);
    if (float_format(o.out)) {
        std::vector<float> encoded(normals.xyz.size());
        for (size_t i = 0; i < encoded.size(); ++i) encoded[i] = normals.xyz[i] * 0.5f + 0.5f;
        io::write_image(o.out, {normals.width, normals.height, 3, io::PixelType::f32, encoded.data()});
    } else {
        const std::vector<uint8_t> rgb = tp::encode_normals_rgb8(normals);
        io::write_image(o.out, {normals.width, normals.height, 3, io::PixelType::u8, rgb.data()});
    }
    return 0;
}

Run define_generate(CLI::App& root) {
    auto o = std::make_shared<Options>();
    CLI::App* gen = root.add_subcommand(
        "generate", "procedural images: reaction-diffusion textures, heightfields, normal maps");
    gen->require_subcommand(1);

    CLI::App* rd = gen->add_subcommand("rd", "Gray-Scott reaction-diffusion texture (Karl Sims' scheme)");
    rd->add_option("--preset", o->preset, "pattern preset (see --list-presets)")->default_val("spots");
    rd->add_option("--size", o->size, "grid size WxH");
    rd->add_option("--steps", o->steps, "time steps")->check(CLI::Range(0, 100000000));
    rd->add_option("--seed", o->seed, "seed of the initial spots or noise")->default_val(1);
    rd->add_option("--frames", o->frames,
                   "write N frames of the growth, evenly spaced in time; --out then needs a "
                   "frame number placeholder (#### or %04d)")
        ->check(CLI::Range(1, 1000000))
        ->default_val(1);
    rd->add_option("--out", o->out, "output image (.png, .exr, .tif)");
    rd->add_flag("--list-presets", o->list_presets, "list the presets and exit");
    rd->add_option("--feed", o->feed, "feed rate f (overrides the preset)");
    rd->add_option("--kill", o->kill, "kill rate k (overrides the preset)");
    rd->add_option("--dt", o->dt, "time step (clamped to the stability limit)")->default_val(1.0f);
    rd->add_option("--anisotropy", o->anisotropy, "in [-1,1]: faster diffusion along x (>0) or y (<0)")
        ->default_val(0.0f);
    rd->add_option("--boundary", o->boundary, "periodic (tileable) or clamped")
        ->check(CLI::IsMember({"periodic", "clamped"}))
        ->default_val("periodic");
    rd->add_option("--init", o->init, "initial condition: spots, noise or image")
        ->check(CLI::IsMember({"spots", "noise", "image"}))
        ->default_val("spots");
    rd->add_option("--init-image", o->init_image, "image whose bright areas seed the pattern (--init image)");
    add_threads_option(*rd, o->threads);

    CLI::App* hf = gen->add_subcommand("heightfield", "fractal terrain heights (16-bit PNG, EXR or TIFF)");
    hf->add_option("--size", o->size, "image size WxH");
    hf->add_option("--seed", o->seed, "noise seed")->default_val(1);
    hf->add_option("--octaves", o->octaves, "fBm octaves")->check(CLI::Range(1, 24))->default_val(8);
    hf->add_option("--cells", o->cells, "noise cells across the width (feature size)")
        ->check(CLI::Range(1, 1 << 20))
        ->default_val(4);
    hf->add_option("--gain", o->gain, "amplitude ratio between octaves")->default_val(0.5f);
    hf->add_option("--relief", o->relief, "fbm, ridged, warped or dunes")
        ->check(CLI::IsMember({"fbm", "ridged", "warped", "dunes"}))
        ->default_val("fbm");
    hf->add_flag("--no-tile", o->no_tile, "a map that does not wrap (no periodic lattice or snapped dune waves)");
    hf->add_option("--erode", o->erode, "thermal erosion iterations (Olsen 2004)")
        ->check(CLI::Range(0, 100000))
        ->default_val(0);
    hf->add_option("--out", o->out, "output image (.png is 16-bit; .exr/.tif float)");
    add_threads_option(*hf, o->threads);

    CLI::App* nm = gen->add_subcommand("normalmap", "tangent-space normal map from a height map");
    nm->add_option("--in", o->in, "height map image (grey; colour is averaged)");
    nm->add_option("--out", o->out, "output image (RGB; (128,128,255) is flat)");
    nm->add_option("--strength", o->strength, "height units per texel multiplier")->default_val(16.0f);
    nm->add_flag("--wrap", o->wrap, "the height map tiles: differences wrap around the edges");

    return [o, rd, hf, nm]() -> int {
        o->feed_given = rd->count("--feed") > 0;
        o->kill_given = rd->count("--kill") > 0;
        if (rd->parsed()) return run_rd(*o);
        if (hf->parsed()) return run_heightfield(*o);
        if (nm->parsed()) return run_normalmap(*o);
        return 2;
    };
}

TESSERA_COMMAND(40, define_generate);

}  // namespace
}  // namespace tessera::cli
