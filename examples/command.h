// Subcommands of the `tessera` command. Each lives in its own cmd_*.cpp and registers itself
// with a static TESSERA_COMMAND(...) so that main.cpp never needs to know the list.
//
// Exit codes (documented in the README): 0 success, 1 runtime failure (tessera::Error: a file
// that cannot be read or written, a render that failed), 2 usage error (bad flags or values).
#pragma once
#include <CLI/CLI.hpp>

#include <tbb/global_control.h>

#include <functional>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "raster/core/camera.h"
#include "raster/pipeline/triangle_setup.h"

namespace tessera::cli {

// A bad flag value found after parsing (e.g. "--size 0x0"): printed like a parse error.
struct UsageError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// Adds one subcommand to `root` and returns the function that runs it once the command line
// has been parsed (options are bound to storage the function owns). Returns the exit code.
using Run = std::function<int()>;
using Define = std::function<Run(CLI::App& root)>;

// `order` sorts the subcommands in --help (lower first).
struct Registration {
    Registration(int order, Define define);
};

struct Entry {
    int order;
    Define define;
};
const std::vector<Entry>& registered_commands();

// Parses "WxH" ("1920x1080") into positive sizes; throws UsageError naming `flag` otherwise.
void parse_size(const std::string& text, const char* flag, int& width, int& height);

// The camera flags of `tessera raster`, shared with the llvmpipe peer (examples/peer), which must
// accept the same command lines: --camera FILE, then --eye/--lookat/--up x,y,z and --fov,
// --near, --far override what the file says.
struct CameraFlags {
    std::string file, eye, lookat, up;
    std::optional<float> fov, near, far;
};
void add_camera_options(CLI::App& command, CameraFlags& flags);

// The camera the flags describe for a width x height image. Throws UsageError for a malformed
// x,y,z, tessera::Error for an unreadable camera file, std::invalid_argument for a camera that
// cannot form a view (validate_camera).
Camera make_camera(const CameraFlags& flags, int width, int height);

// The camera for geometry inside the box [lower, upper]: the flags' own when they give a pose
// (--camera or --eye); otherwise the box framed (raster/asset/framing.h) with the flags'
// --lookat, --up, --fov, --near and --far applied over it, printed on stderr as the flags that
// give it again ("tessera: camera (framed): --eye ..."). Without a box (an empty mesh), make_camera.
struct Box {
    glm::vec3 lower, upper;
};
Camera make_camera_or_frame(const CameraFlags& flags, int width, int height, const std::optional<Box>& box);

// "none" | "back" | "front" (--cull); UsageError otherwise.
pipeline::CullMode parse_cull(const std::string& text);

// The median of `values` (of an even count: the mean of the middle two); 0 when empty.
double median(std::vector<double> values);

// Prints "frame_ms median=X min=Y max=Z" for a non-empty `ms`, the line `tessera raster
// --repeat` and the peer print for the benchmark scripts.
void print_frame_times(const std::vector<double>& ms);

// Adds the common "--threads N" option (0, the default, means every core) to `command`.
void add_threads_option(CLI::App& command, int& threads);

// Adds "--samples 1|4|8|16" (MSAA samples per pixel, pipeline/sample_pattern.h); `what_default`
// ends its help text.
void add_samples_option(CLI::App& command, int& samples, const std::string& what_default);

// Caps oneTBB's worker count for as long as the returned guard lives (0: no cap).
std::unique_ptr<tbb::global_control> limit_threads(int threads);

}  // namespace tessera::cli

#define TESSERA_CONCAT_(a, b) a##b
#define TESSERA_CONCAT(a, b) TESSERA_CONCAT_(a, b)
#define TESSERA_COMMAND(order, define) \
    static const ::tessera::cli::Registration TESSERA_CONCAT(tessera_command_, __LINE__){order, define}
