// The two inputs of `tessera raster` and its peer: an OBJ mesh and a CAM.txt camera, read
// with issue 3's rules so that both renderers see the same triangles in the same order.
#pragma once
#include <filesystem>

#include "raster/camera.h"
#include "raster/mesh.h"

namespace tessera::peer {

// Faces are fan-triangulated from their first vertex; a triangle's id is its position in the
// file after triangulation. Normals (uvs) are kept only when every corner has one; corners
// sharing a (position, normal, uv) triple share a vertex. Throws tessera::Error naming the
// file and the reason.
Mesh load_obj(const std::filesystem::path& path);

// One key per line: `eye x y z`, `lookat x y z`, `up x y z`, `fovy_deg f`, `near n`, `far f`;
// blank lines and lines starting with '#' are ignored, absent keys keep Camera's defaults.
// The aspect is not in the file (the image size sets it). Throws tessera::Error.
Camera load_camera(const std::filesystem::path& path);

}  // namespace tessera::peer
