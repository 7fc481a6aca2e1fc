// Fuzz target: the model importer's entry (raster/io/model_file.h, Assimp behind it) on
// arbitrary bytes. The first byte picks the format (the file extension Assimp is told), the
// rest is the file. Properties of every accepted model: each index names a vertex of its part,
// attribute streams are empty or one per position, every position is finite, within
// kMaxModelCoordinate and inside the reported bounds, the stats agree with the parts, and
// every material and embedded-texture reference is in range.
#include <unistd.h>

#include <cmath>
#include <iterator>
#include <filesystem>
#include <fstream>

#include "raster/core/error.h"
#include "raster/io/model_file.h"
#include "tests/fuzz/fuzz_target.h"

namespace tessera::fuzz {
namespace {

constexpr const char* kFormats[] = {".gltf", ".glb", ".obj", ".ply", ".stl", ".off", ".fbx", ".dae"};

std::string check(const io::ModelFile& model) {
    size_t triangles = 0, vertices = 0;
    for (const io::ModelPart& part : model.parts) {
        const Mesh& m = part.mesh;
        if (m.indices.empty() || m.indices.size() % 3 != 0) return "a part with no or partial triangles";
        for (uint32_t i : m.indices)
            if (i >= m.positions.size()) return "index " + std::to_string(i) + " out of range";
        if (!m.normals.empty() && m.normals.size() != m.positions.size()) return "normals not one per position";
        if (!m.uvs.empty() && m.uvs.size() != m.positions.size()) return "uvs not one per position";
        if (!m.tangents.empty() && m.tangents.size() != m.positions.size()) return "tangents not one per position";
        for (const glm::vec3& p : m.positions)
            for (int k = 0; k < 3; ++k) {
                if (!std::isfinite(p[k]) || std::fabs(p[k]) > io::kMaxModelCoordinate) return "bad position kept";
                if (p[k] < model.lower[k] || p[k] > model.upper[k]) return "a position outside the bounds";
            }
        if (part.material >= model.materials.size()) return "material index out of range";
        triangles += m.triangle_count();
        vertices += m.vertex_count();
    }
    if (model.parts.empty()) return "a model without parts was accepted";
    if (triangles != model.stats.triangles || vertices != model.stats.vertices) return "stats disagree with the parts";
    for (const io::ModelMaterial& m : model.materials)
        for (const auto* ref : {&m.base_colour_texture, &m.normal_texture, &m.metallic_roughness_texture})
            if (*ref && (*ref)->embedded >= int(model.images.size())) return "embedded texture index out of range";
    return "";
}

}  // namespace

std::string model_input(Bytes data) {
    if (data.empty()) return "";
    // A private file per process: libFuzzer's -jobs and -fork runs share /tmp.
    const std::filesystem::path path = std::filesystem::temp_directory_path() /
                                       ("tessera_fuzz_model_" + std::to_string(::getpid()) +
                                        kFormats[data[0] % std::size(kFormats)]);
    {
        std::ofstream out(path, std::ios::binary | std::ios::trunc);
        out.write(reinterpret_cast<const char*>(data.data() + 1), std::streamsize(data.size() - 1));
    }
    std::string broken;
    try {
        broken = check(io::read_model(path));
    } catch (const Error&) {
        // rejected with a message: the expected outcome for malformed files
    }
    std::error_code ec;
    std::filesystem::remove(path, ec);
    return broken;
}

}  // namespace tessera::fuzz

TESSERA_FUZZ_ENTRY(model_input)
