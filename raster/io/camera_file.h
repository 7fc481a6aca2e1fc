// CAM.txt, the camera file of `tessera raster` (issue 3): one key per line,
//   eye x y z | lookat x y z | up x y z | fovy_deg f | near n | far f
// (vertical field of view in degrees; the aspect ratio comes from the image size). Blank
// lines and lines starting with '#' are ignored; keys not given keep their current value.
#pragma once
#include <filesystem>
#include <string>

#include "raster/core/camera.h"

namespace tessera::io {

// Applies the keys of `text` to `camera`; throws tessera::Error naming `name` and the line.
void parse_camera(const std::string& text, const std::string& name, Camera& camera);

// Reads the file at `path` into `camera` (tessera::Error when unreadable or malformed).
void read_camera_file(const std::filesystem::path& path, Camera& camera);

// Throws std::invalid_argument when the camera cannot form a view (eye == lookat, up parallel
// to the view direction, fov outside (0, 180), near <= 0 or far <= near, non-finite values).
void validate_camera(const Camera& camera);

}  // namespace tessera::io
