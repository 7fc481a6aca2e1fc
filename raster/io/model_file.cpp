#include "raster/io/model_file.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <utility>

#include "raster/core/error.h"
#include "raster/core/input_file.h"
#include "raster/io/assimp_reader.h"
#include "raster/io/header_check.h"
#include "raster/io/isolated_call.h"
#include "raster/io/mesh_weld.h"
#include "raster/io/raw_model.h"

namespace tessera::io {
namespace {

using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); }

[[noreturn]] void fail(const std::filesystem::path& path, const std::string& what) {
    throw Error("cannot read '" + path.string() + "': " + what);
}

// The reader's limits: generous for real files (Assimp reads a 1M-triangle, 117 MB OBJ in about
// 2.5 s and 400 MB here), tight enough that a file sending a parser into an endless loop or an
// allocation of what its header merely claims fails in seconds. A .gltf counts the .bin files
// beside it, where its data usually lives.
IsolationLimits limits_for(const std::filesystem::path& path) {
    std::error_code ec;
    uintmax_t bytes = std::filesystem::file_size(path, ec);
    if (ec) bytes = 0;
    std::string ext = path.extension().string();
    for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
    if (ext == ".gltf")
        for (const auto& entry : std::filesystem::directory_iterator(path.parent_path(), ec)) {
            std::error_code e2;
            if (entry.path().extension() == ".bin" && entry.is_regular_file(e2)) bytes += entry.file_size(e2);
        }
    const double megabytes = double(bytes) / double(1 << 20);
    IsolationLimits limits;
    limits.seconds = 10.0 + megabytes;
    limits.resident_bytes = std::max<size_t>(size_t(2) << 30, size_t(bytes) * 16);
    return limits;
}

bool good(const glm::vec3& p) {
    return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z) && std::fabs(p.x) <= kMaxModelCoordinate &&
           std::fabs(p.y) <= kMaxModelCoordinate && std::fabs(p.z) <= kMaxModelCoordinate;
}

glm::vec3 unit_or_zero(glm::vec3 v) {
    const float length = glm::length(v);
    return std::isfinite(length) && length > 0.0f ? v / length : glm::vec3(0.0f);
}

// One mesh placed by its node's transform: the triangles kept, and only the vertices they use,
// in the order of first use, then welded.
Mesh place_mesh(const RawMesh& in, const glm::mat4& transform, ModelStats& stats) {
    const glm::mat3 linear(transform);
    const glm::mat3 normal_matrix = glm::transpose(glm::inverse(linear));
    const bool mirrored = glm::determinant(linear) < 0.0f;
    const size_t n = in.positions.size();
    const auto position = [&](uint32_t v) { return glm::vec3(transform * glm::vec4(in.positions[v], 1.0f)); };
    // Per input vertex: 0 not seen yet, 1 bad coordinate, else its new index + 2.
    std::vector<uint32_t> remap(n, 0);
    std::vector<uint32_t> order;
    Mesh mesh;
    mesh.indices.reserve(in.triangles.size());
    for (size_t t = 0; t + 2 < in.triangles.size(); t += 3) {
        uint32_t corner[3];
        bool ok = true;
        for (int k = 0; k < 3; ++k) {
            const uint32_t v = in.triangles[t + size_t(k)];
            if (v >= n) {  // Assimp's validation rejects these; counted, never read
                ok = false;
                break;
            }
            if (remap[v] == 0) {
                if (good(position(v))) {
                    remap[v] = uint32_t(order.size()) + 2;
                    order.push_back(v);
                } else {
                    remap[v] = 1;
                }
            }
            ok &= remap[v] != 1;
            corner[k] = remap[v] - 2;
        }
        if (!ok) {
            ++stats.skipped_triangles;
            continue;
        }
        mesh.indices.insert(mesh.indices.end(), {corner[0], corner[mirrored ? 2 : 1], corner[mirrored ? 1 : 2]});
    }

    const size_t used = order.size();
    const bool normals = in.normals.size() == n;
    const bool uvs = in.uvs.size() == n;
    const bool tangents = normals && in.tangents.size() == n && in.bitangents.size() == n;
    mesh.positions.resize(used);
    if (normals) mesh.normals.resize(used);
    if (uvs) mesh.uvs.resize(used);
    if (tangents) mesh.tangents.resize(used);
    for (size_t k = 0; k < used; ++k) {
        const uint32_t v = order[k];
        mesh.positions[k] = position(v);
        if (normals) mesh.normals[k] = unit_or_zero(normal_matrix * in.normals[v]);
        if (uvs) {
            const glm::vec2 t = in.uvs[v];
            mesh.uvs[k] = std::isfinite(t.x) && std::isfinite(t.y) ? t : glm::vec2(0.0f);
        }
        if (tangents) {
            // w: which side of the (normal, tangent) plane the bitangent lies on (glTF TANGENT.w).
            const float w = glm::dot(glm::cross(in.normals[v], in.tangents[v]), in.bitangents[v]) < 0.0f ? -1.0f : 1.0f;
            mesh.tangents[k] = glm::vec4(unit_or_zero(linear * in.tangents[v]), mirrored ? -w : w);
        }
    }
    weld_vertices(mesh);
    return mesh;
}

// Factors from a broken file (NaN, negative, above 1) brought into their ranges.
void sanitise(ModelMaterial& m) {
    const auto unit = [](float x, float fallback) { return std::isfinite(x) ? std::clamp(x, 0.0f, 1.0f) : fallback; };
    for (int c = 0; c < 4; ++c) m.base_colour[c] = unit(m.base_colour[c], 1.0f);
    for (int c = 0; c < 3; ++c) m.specular[c] = unit(m.specular[c], 0.0f);
    m.metallic = unit(m.metallic, 1.0f);
    m.roughness = unit(m.roughness, 1.0f);
    m.alpha_cutoff = unit(m.alpha_cutoff, 0.5f);
    m.shininess = std::isfinite(m.shininess) ? std::clamp(m.shininess, 0.0f, 1e4f) : 0.0f;
}

ModelFile convert(RawModel raw, const std::filesystem::path& path) {
    ModelFile model;
    model.path = path;
    model.images = std::move(raw.images);
    model.materials = std::move(raw.materials);
    model.warnings = std::move(raw.warnings);
    for (ModelMaterial& m : model.materials) {
        sanitise(m);
        for (auto* ref : {&m.base_colour_texture, &m.normal_texture, &m.metallic_roughness_texture})
            if (*ref && (*ref)->embedded >= int(model.images.size())) ref->reset();
    }
    if (model.materials.empty()) model.materials.emplace_back();

    // Node transforms compose down the tree (a parent comes before its children).
    std::vector<glm::mat4> world(raw.nodes.size());
    size_t vertices = 0;
    for (size_t i = 0; i < raw.nodes.size(); ++i) {
        const RawNode& node = raw.nodes[i];
        const bool has_parent = node.parent >= 0 && size_t(node.parent) < i;
        world[i] = has_parent ? world[size_t(node.parent)] * node.transform : node.transform;
        for (const uint32_t m : node.meshes) {
            if (m >= raw.meshes.size()) continue;
            const RawMesh& mesh = raw.meshes[m];
            model.stats.skipped_primitives += mesh.points_and_lines;
            if (mesh.triangles.empty()) continue;
            ModelPart part;
            part.name = node.name + (mesh.name.empty() ? "" : "/" + mesh.name);
            part.material = mesh.material < model.materials.size() ? mesh.material : 0;
            part.mesh = place_mesh(mesh, world[i], model.stats);
            if (part.mesh.indices.empty()) continue;
            vertices += part.mesh.positions.size();
            if (vertices > std::numeric_limits<uint32_t>::max())
                fail(path, "more than 2^32 vertices once its node tree is expanded");
            model.parts.push_back(std::move(part));
        }
    }
    if (model.parts.empty()) {
        if (model.stats.skipped_triangles)
            fail(path, "every triangle has a corner with a NaN, infinite or huge coordinate");
        if (model.stats.skipped_primitives)
            fail(path, "no triangles, only " + std::to_string(model.stats.skipped_primitives) + " points and lines");
        fail(path, "no triangles in the file's node tree");
    }
    model.lower = model.upper = model.parts[0].mesh.positions[0];
    for (const ModelPart& part : model.parts) {
        model.stats.triangles += part.mesh.triangle_count();
        model.stats.vertices += part.mesh.vertex_count();
        for (const glm::vec3& p : part.mesh.positions) {
            model.lower = glm::min(model.lower, p);
            model.upper = glm::max(model.upper, p);
        }
    }
    return model;
}

}  // namespace

ModelFile read_model(const std::filesystem::path& path) {
    check_input_file(path);  // "no such file", or a directory, device or FIFO refused at once
    if (!model_format_supported(path))
        fail(path, "no model reader for '" + path.extension().string() +
                       "' (glTF 2.0, OBJ, PLY, STL, FBX, Collada and the other formats Assimp reads)");
    if (const auto problem = header_problem(path)) fail(path, *problem);

    // Assimp runs in a child process: its parsers have bugs that loop forever or crash on
    // malformed files (found by fuzzing this entry), and those must not take tessera down.
    const auto t_read = Clock::now();
    const IsolatedResult result =
        run_isolated([&path] { return to_bytes(read_with_assimp(path)); }, limits_for(path));
    if (!result.ok) fail(path, result.threw ? result.failure : "the importer (Assimp) " + result.failure);
    const double read_ms = ms_since(t_read);

    const auto t_convert = Clock::now();
    ModelFile model = convert(raw_model_from_bytes(result.bytes), path);
    model.stats.read_ms = read_ms;
    model.stats.convert_ms = ms_since(t_convert);
    return model;
}

bool model_format_supported(const std::filesystem::path& path) {
    return assimp_reads_extension(path.extension().string());
}

Mesh merge_parts(const ModelFile& model) {
    // Parts without normals, among parts with them, are given their face normals (their
    // triangles then own their corners), which is what the shading would use for them.
    bool normals = false, uvs = false, tangents = !model.parts.empty();
    for (const ModelPart& p : model.parts) {
        normals |= !p.mesh.normals.empty();
        uvs |= !p.mesh.uvs.empty();
        tangents &= !p.mesh.tangents.empty();
    }
    Mesh out;
    for (const ModelPart& p : model.parts) {
        const Mesh& m = p.mesh;
        if (normals && m.normals.empty()) {
            for (size_t t = 0; t < m.triangle_count(); ++t) {
                const uint32_t* i = &m.indices[3 * t];
                const glm::vec3 n = unit_or_zero(
                    glm::cross(m.positions[i[1]] - m.positions[i[0]], m.positions[i[2]] - m.positions[i[0]]));
                for (int k = 0; k < 3; ++k) {
                    out.indices.push_back(uint32_t(out.positions.size()));
                    out.positions.push_back(m.positions[i[k]]);
                    out.normals.push_back(n);
                    if (uvs) out.uvs.push_back(m.uvs.empty() ? glm::vec2(0.0f) : m.uvs[i[k]]);
                }
            }
            continue;
        }
        const uint32_t base = uint32_t(out.positions.size());
        out.positions.insert(out.positions.end(), m.positions.begin(), m.positions.end());
        if (normals) out.normals.insert(out.normals.end(), m.normals.begin(), m.normals.end());
        if (uvs) {
            if (m.uvs.empty()) out.uvs.resize(out.positions.size(), glm::vec2(0.0f));
            else out.uvs.insert(out.uvs.end(), m.uvs.begin(), m.uvs.end());
        }
        if (tangents) out.tangents.insert(out.tangents.end(), m.tangents.begin(), m.tangents.end());
        for (const uint32_t i : m.indices) out.indices.push_back(base + i);
    }
    return out;
}

}  // namespace tessera::io
