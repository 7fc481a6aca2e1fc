#include "raster/io/camera_file.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include "raster/core/direction.h"
#include "raster/core/error.h"
#include "raster/core/input_file.h"

namespace tessera::io {

void parse_camera(const std::string& text, const std::string& name, Camera& camera) {
    std::istringstream in(text);
    std::string line;
    for (size_t number = 1; std::getline(in, line); ++number) {
        std::istringstream fields(line);
        std::string key;
        if (!(fields >> key) || key[0] == '#') continue;
        auto bad = [&](const std::string& why) {
            return Error("cannot read '" + name + "': line " + std::to_string(number) + ": " + why);
        };
        auto read = [&](float* values, int n) {
            for (int i = 0; i < n; ++i)
                if (!(fields >> values[i])) throw bad("'" + key + "' expects " + std::to_string(n) + " numbers");
            std::string extra;
            if (fields >> extra) throw bad("unexpected '" + extra + "' after '" + key + "'");
        };
        if (key == "eye") read(&camera.eye.x, 3);
        else if (key == "lookat") read(&camera.lookat.x, 3);
        else if (key == "up") read(&camera.up.x, 3);
        else if (key == "fovy_deg") read(&camera.fovy_deg, 1);
        else if (key == "near") read(&camera.near, 1);
        else if (key == "far") read(&camera.far, 1);
        else throw bad("unknown key '" + key + "' (expected eye, lookat, up, fovy_deg, near, far)");
    }
}

void read_camera_file(const std::filesystem::path& path, Camera& camera) {
    InputFile file(path);  // a device, FIFO or directory is refused at once
    // A camera file is a few lines; a megabyte is no camera file.
    const std::string text = file.read(size_t(1) << 20);
    if (file.size() > text.size()) throw Error("cannot read '" + path.string() + "': not a camera file (too large)");
    parse_camera(text, path.string(), camera);
}

void validate_camera(const Camera& c) {
    auto finite = [](glm::vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); };
    if (!finite(c.eye) || !finite(c.lookat) || !finite(c.up) || !std::isfinite(c.fovy_deg) ||
        !std::isfinite(c.near) || !std::isfinite(c.far))
        throw std::invalid_argument("camera values must be finite numbers");
    // Directions are compared at unit length, scaled first (core/direction.h): an up of
    // [0, 3e38, 0] is as good as [0, 1, 0], and nothing here overflows.
    const glm::vec3 forward = c.lookat - c.eye;
    if (!finite(forward)) throw std::invalid_argument("camera eye and lookat are too far apart");
    const auto view = unit_direction(forward);
    if (!view) throw std::invalid_argument("camera eye and lookat are the same point");
    const auto up = unit_direction(c.up);
    if (!up || !(glm::length(glm::cross(*view, *up)) > 1e-6f))
        throw std::invalid_argument("camera up is zero or parallel to the view direction");
    if (!(c.fovy_deg > 0.0f && c.fovy_deg < 180.0f))
        throw std::invalid_argument("field of view must be in (0, 180) degrees");
    if (!(c.near > 0.0f) || !(c.far > c.near))
        throw std::invalid_argument("near must be > 0 and far > near");
}

}  // namespace tessera::io
