// Wavefront OBJ in and out. Reading goes through tinyobjloader (Debian libtinyobjloader-dev);
// faces are fan-triangulated from their first vertex, and a triangle's id is its order in the
// file after triangulation (what `tessera raster --out-id` writes).
//
// Bad input: an unreadable file, a malformed v/vt/vn/f line or an index out of range is a
// tessera::Error naming the file and line. Vertices with NaN, infinite or huge coordinates
// (beyond kMaxObjCoordinate) are set to the origin and every triangle using one is made
// degenerate (all three indices equal, never drawn) and counted, so ids stay stable.
#pragma once
#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>

#include "raster/core/mesh.h"

namespace tessera::io {

inline constexpr float kMaxObjCoordinate = 1e18f;

struct ObjLoadStats {
    size_t faces = 0;
    size_t triangles = 0;
    size_t bad_vertices = 0;       // NaN, Inf or huge
    size_t skipped_triangles = 0;  // made degenerate because they use a bad vertex
};

// Throws tessera::Error ("cannot read 'PATH': ...").
Mesh load_obj(const std::filesystem::path& path, ObjLoadStats* stats = nullptr);

// The same, from text; `name` is used in error messages.
Mesh parse_obj(const std::string& text, const std::string& name, ObjLoadStats* stats = nullptr);

// Writes `mesh` as OBJ (v, vn, vt when present, f with 1-based indices), atomically.
void write_obj(const std::filesystem::path& path, const Mesh& mesh);

}  // namespace tessera::io
