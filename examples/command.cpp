#include "examples/command.h"

#include <algorithm>
#include <charconv>
#include <cstdio>
#include <sstream>

#include "raster/asset/framing.h"
#include "raster/core/direction.h"
#include "raster/io/camera_file.h"

namespace tessera::cli {

namespace {
std::vector<Entry>& registry() {
    static std::vector<Entry> entries;  // function-local: safe from static-init order
    return entries;
}
}  // namespace

Registration::Registration(int order, Define define) {
    registry().push_back({order, std::move(define)});
}

const std::vector<Entry>& registered_commands() { return registry(); }

void parse_size(const std::string& text, const char* flag, int& width, int& height) {
    const auto x = text.find_first_of("xX");
    auto number = [&](std::string_view part, int& value) {
        const char* end = part.data() + part.size();
        auto [ptr, ec] = std::from_chars(part.data(), end, value);
        return ec == std::errc() && ptr == end && value > 0;
    };
    std::string_view all(text);
    if (x == std::string::npos || !number(all.substr(0, x), width) ||
        !number(all.substr(x + 1), height))
        throw UsageError(std::string(flag) + " expects WIDTHxHEIGHT with positive integers, got '" +
                         text + "'");
}

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

}  // namespace

void add_camera_options(CLI::App& command, CameraFlags& flags) {
    command.add_option("--camera", flags.file, "camera file: lines 'eye x y z', 'lookat x y z', 'up x y z', "
                                               "'fovy_deg f', 'near n', 'far f'");
    command.add_option("--eye", flags.eye, "camera position x,y,z (overrides the file)");
    command.add_option("--lookat", flags.lookat, "point looked at x,y,z");
    command.add_option("--up", flags.up, "up direction x,y,z");
    command.add_option("--fov", flags.fov, "vertical field of view, degrees");
    command.add_option("--near", flags.near, "near plane distance");
    command.add_option("--far", flags.far, "far plane distance");
}

Camera make_camera(const CameraFlags& flags, int width, int height) {
    Camera camera;
    if (!flags.file.empty()) io::read_camera_file(flags.file, camera);
    if (!flags.eye.empty()) camera.eye = parse_vec3(flags.eye, "--eye");
    if (!flags.lookat.empty()) camera.lookat = parse_vec3(flags.lookat, "--lookat");
    if (!flags.up.empty()) camera.up = parse_vec3(flags.up, "--up");
    if (flags.fov) camera.fovy_deg = *flags.fov;
    if (flags.near) camera.near = *flags.near;
    if (flags.far) camera.far = *flags.far;
    camera.aspect = float(width) / float(height);
    io::validate_camera(camera);
    camera.up = *normalisable(camera.up);  // any length (core/direction.h)
    return camera;
}

Camera make_camera_or_frame(const CameraFlags& flags, int width, int height, const std::optional<Box>& box) {
    if (!box || !flags.file.empty() || !flags.eye.empty()) return make_camera(flags, width, height);
    Camera camera;
    try {
        camera = asset::frame_box(box->lower, box->upper, float(width) / float(height), flags.fov.value_or(45.0f));
    } catch (const std::invalid_argument& e) {
        throw UsageError(std::string("--fov: ") + e.what());
    }
    if (!flags.lookat.empty()) camera.lookat = parse_vec3(flags.lookat, "--lookat");
    if (!flags.up.empty()) camera.up = parse_vec3(flags.up, "--up");
    if (flags.near) camera.near = *flags.near;
    if (flags.far) camera.far = *flags.far;
    io::validate_camera(camera);
    std::fprintf(stderr, "tessera: camera (framed): %s\n", asset::camera_flags(camera).c_str());
    return camera;
}

pipeline::CullMode parse_cull(const std::string& text) {
    if (text == "none") return pipeline::CullMode::none;
    if (text == "back") return pipeline::CullMode::back;
    if (text == "front") return pipeline::CullMode::front;
    throw UsageError("--cull expects none, back or front, got '" + text + "'");
}

double median(std::vector<double> values) {
    if (values.empty()) return 0.0;
    std::sort(values.begin(), values.end());
    const size_t n = values.size();
    return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

void print_frame_times(const std::vector<double>& ms) {
    const auto [least, most] = std::minmax_element(ms.begin(), ms.end());
    std::printf("frame_ms median=%.3f min=%.3f max=%.3f\n", median(ms), *least, *most);
}

void add_threads_option(CLI::App& command, int& threads) {
    command.add_option("--threads", threads, "worker threads (0 = all cores)")
        ->check(CLI::Range(0, 4096))
        ->default_val(0);
}

void add_samples_option(CLI::App& command, int& samples, const std::string& what_default) {
    command
        .add_option("--samples", samples,
                    "MSAA samples per pixel: 1, 4, 8 or 16 at the D3D/Vulkan standard positions; each surface "
                    "of a pixel is shaded once and weighted by the samples it covers " + what_default)
        ->check(CLI::IsMember({1, 4, 8, 16}));
}

std::unique_ptr<tbb::global_control> limit_threads(int threads) {
    if (threads <= 0) return nullptr;
    return std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                 size_t(threads));
}

}  // namespace tessera::cli
