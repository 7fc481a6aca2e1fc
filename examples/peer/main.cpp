// tessera-llvmpipe: the peer renderer. Renders one OBJ with one camera through Mesa's llvmpipe
// (OSMesa), with the flags, shading and outputs of `tessera raster` (issue 3), so that the two
// can be timed on the same work (--repeat) and compared pixel for pixel (--out-id).
#include <CLI/CLI.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>

#include "examples/peer/gl_frame.h"
#include "examples/peer/osmesa_context.h"
#include "examples/command.h"
#include "raster/io/image_io.h"
#include "raster/io/obj_loader.h"
#include "raster/pipeline/viewport.h"
#include "raster/io/visibility_io.h"

namespace {

using namespace tessera;
using namespace tessera::peer;

struct Options {
    std::string mesh, size = "1920x1080";
    cli::CameraFlags camera;
    std::string shade = "phong", cull = "none";
    int threads = 0;
    std::string out_color, out_id, out_depth;
    int repeat = 0;
    int samples = 1;
    bool stats = false;
};

int run(const Options& o) {
    int width = 0, height = 0;
    cli::parse_size(o.size, "--size", width, height);
    const pipeline::Viewport limits(width, height);  // the same size limits as tessera raster
    FrameOptions frame_options;
    frame_options.width = width;
    frame_options.height = height;
    frame_options.shade = shade::parse_shade_mode(o.shade);
    frame_options.cull = cli::parse_cull(o.cull);
    frame_options.triangle_ids = !o.out_id.empty();
    frame_options.samples = o.samples;
    // As `tessera raster --shade id --samples N`: a multisampled frame is compared by its ids.
    if (o.samples > 1 && (!o.out_color.empty() || !o.out_depth.empty()))
        throw cli::UsageError("--samples N writes per-sample ids (--out-id), not --out-color or --out-depth");
    if (!o.out_color.empty() && !io::image_format_supported(o.out_color))
        throw cli::UsageError("--out-color: no image writer for '" + o.out_color + "'");
    const Camera camera = cli::make_camera(o.camera, width, height);
    const Mesh mesh = io::load_obj(o.mesh);

    OsMesaContext context(o.threads);  // sets LP_NUM_THREADS before llvmpipe starts
    GlFrame frame(mesh, camera, frame_options);

    // The first frame JIT-compiles llvmpipe's shader variants; it is not a steady-state frame,
    // so it is rendered before the timed ones (and is the only frame without --repeat).
    frame.render();
    std::vector<double> frame_ms;
    for (int i = 0; i < o.repeat; ++i) {
        const auto start = std::chrono::steady_clock::now();
        frame.render();  // clear + draw + glFinish
        frame_ms.push_back(
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                .count());
    }
    if (!frame_ms.empty()) cli::print_frame_times(frame_ms);
    if (o.stats)
        std::printf("peer: %s, OpenGL %s (%s profile), LP_NUM_THREADS=%s, %zu triangles, %dx%d\n",
                    context.renderer().c_str(), context.version().c_str(),
                    context.core_profile() ? "core" : "compatibility",
                    std::getenv("LP_NUM_THREADS") ? std::getenv("LP_NUM_THREADS") : "default",
                    mesh.triangle_count(), width, height);
    if (o.stats && o.samples > 1) {
        std::printf("peer: %d samples at (GL_SAMPLE_POSITION, pixel units, top-down rows)", o.samples);
        for (const glm::vec2& p : frame.gl_sample_positions()) std::printf(" (%g,%g)", p.x, p.y);
        const std::string mismatch = frame.sample_position_mismatch();
        std::printf("; %s\n", mismatch.empty() ? "tessera's positions" : mismatch.c_str());
    }

    if (!o.out_color.empty()) {
        const std::vector<uint8_t> rgb = frame.colour_rgb8();
        io::write_image(o.out_color, io::ImageView{width, height, 3, io::PixelType::u8, rgb.data(), /*srgb=*/true});
    }
    if (!o.out_id.empty() || !o.out_depth.empty()) {
        const VisibilityBuffer visibility = frame.visibility();
        if (!o.out_id.empty()) io::write_tsid(o.out_id, visibility);
        if (!o.out_depth.empty()) io::write_depth_pfm(o.out_depth, visibility);
    }
    return 0;
}

void print_error(const char* message, const char* hint) {
    std::fprintf(stderr, "tessera-llvmpipe: error: %s\n", message);
    if (hint) std::fprintf(stderr, "hint: %s\n", hint);
}

}  // namespace

int main(int argc, char** argv) {
    Options o;
    CLI::App app{"tessera-llvmpipe: renders like 'tessera raster', through Mesa's llvmpipe "
                 "(OSMesa), for timing and pixel comparisons",
                 "tessera-llvmpipe"};
    app.add_option("--mesh", o.mesh, "OBJ file (faces fan-triangulated; triangle id = order in file)")
        ->required();
    app.add_option("--size", o.size, "image size WIDTHxHEIGHT")->default_val("1920x1080");
    tessera::cli::add_camera_options(app, o.camera);
    app.add_option("--shade", o.shade, "id | depth | normal | phong")->default_val("phong");
    app.add_option("--cull", o.cull, "none | back | front (front faces are counter-clockwise)")
        ->default_val("none");
    tessera::cli::add_threads_option(app, o.threads);
    app.add_option("--out-color", o.out_color, "colour image (PNG, EXR, TIFF...; 8-bit RGB)");
    app.add_option("--out-id", o.out_id,
                   "triangle ids (TSID: header, then uint32 LE per pixel, or per sample with --samples)");
    app.add_option("--samples", o.samples,
                   "MSAA samples per pixel (multisample targets; refused unless llvmpipe has that count "
                   "for every target); --out-id then writes every sample's id in tessera's sample order")
        ->check(CLI::IsMember({1, 4, 8, 16}))
        ->default_val(1);
    app.add_option("--out-depth", o.out_depth, "window depth (PFM, rows bottom to top)");
    app.add_option("--repeat", o.repeat, "render K timed frames and print 'frame_ms median=X min=Y max=Z'")
        ->check(CLI::Range(1, 100000));
    app.add_flag("--stats", o.stats, "print the renderer, its threads and the triangle count");
    try {
        app.parse(argc, argv);
    } catch (const CLI::Success& done) {
        return app.exit(done);
    } catch (const CLI::ParseError& error) {
        std::string message = error.what();
        std::replace(message.begin(), message.end(), '\n', ' ');
        print_error(message.c_str(), "run 'tessera-llvmpipe --help' for usage");
        return 2;
    }
    try {
        return run(o);
    } catch (const tessera::cli::UsageError& error) {
        print_error(error.what(), "run 'tessera-llvmpipe --help' for usage");
        return 2;
    } catch (const std::invalid_argument& error) {
        print_error(error.what(), "run 'tessera-llvmpipe --help' for usage");
        return 2;
    } catch (const std::bad_alloc&) {
        print_error("out of memory (try a smaller --size)", nullptr);
        return 1;
    } catch (const std::exception& error) {
        print_error(error.what(), nullptr);
        return 1;
    }
}
