// Fuzz target: the OBJ loader (raster/obj_loader.h) on arbitrary text.
// Properties of every accepted file: each index names a vertex, attribute streams are empty
// or one per position, every position is finite and within kMaxObjCoordinate (bad ones are
// replaced by the origin), and the counts in ObjLoadStats agree with the mesh.
#include <cmath>
#include <stdexcept>

#include "raster/core/error.h"
#include "raster/io/obj_loader.h"
#include "tests/fuzz/fuzz_target.h"

namespace tessera::fuzz {

std::string obj_input(Bytes data) {
    const std::string text(reinterpret_cast<const char*>(data.data()), data.size());
    io::ObjLoadStats stats;
    Mesh mesh;
    try {
        mesh = io::parse_obj(text, "fuzz.obj", &stats);
    } catch (const Error&) {
        return "";  // rejected with a message: the expected outcome for malformed files
    }
    if (mesh.indices.size() % 3 != 0) return "index count is not a multiple of 3";
    if (mesh.triangle_count() != stats.triangles) return "stats.triangles disagrees with the mesh";
    if (stats.skipped_triangles > stats.triangles) return "more skipped triangles than triangles";
    for (uint32_t i : mesh.indices)
        if (i >= mesh.positions.size()) return "index " + std::to_string(i) + " out of range";
    if (!mesh.normals.empty() && mesh.normals.size() != mesh.positions.size()) return "normals not one per position";
    if (!mesh.uvs.empty() && mesh.uvs.size() != mesh.positions.size()) return "uvs not one per position";
    for (const glm::vec3& p : mesh.positions)
        for (int k = 0; k < 3; ++k)
            if (!std::isfinite(p[k]) || std::fabs(p[k]) > io::kMaxObjCoordinate) return "bad position kept in the mesh";
    return "";
}

}  // namespace tessera::fuzz

TESSERA_FUZZ_ENTRY(obj_input)
