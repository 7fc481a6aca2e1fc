#include "bench/peer/scene_input.h"

#include <tiny_obj_loader.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <unordered_map>

#include "raster/error.h"

namespace tessera::peer {
namespace {

std::string one_line(std::string text) {
    while (!text.empty() && (text.back() == '\n' || text.back() == '\r')) text.pop_back();
    for (char& c : text)
        if (c == '\n' || c == '\r') c = ' ';
    return text;
}

// A corner's (position, normal, uv) indices packed into one key for vertex sharing.
struct CornerHash {
    size_t operator()(const tinyobj::index_t& i) const {
        return std::hash<uint64_t>()((uint64_t(uint32_t(i.vertex_index)) << 32) ^
                                     (uint64_t(uint32_t(i.normal_index)) << 16) ^
                                     uint64_t(uint32_t(i.texcoord_index)));
    }
};
struct CornerEqual {
    bool operator()(const tinyobj::index_t& a, const tinyobj::index_t& b) const {
        return a.vertex_index == b.vertex_index && a.normal_index == b.normal_index &&
               a.texcoord_index == b.texcoord_index;
    }
};

}  // namespace

Mesh load_obj(const std::filesystem::path& path) {
    const std::string name = "cannot read '" + path.string() + "': ";
    tinyobj::ObjReaderConfig config;
    config.triangulate = false;  // fan triangulation below, in file order
    config.vertex_color = false;
    tinyobj::ObjReader reader;
    if (!reader.ParseFromFile(path.string(), config))
        throw Error(name + one_line(reader.Error().empty() ? "not an OBJ file" : reader.Error()));
    const tinyobj::attrib_t& attrib = reader.GetAttrib();
    const size_t positions = attrib.vertices.size() / 3, normals = attrib.normals.size() / 3,
                 uvs = attrib.texcoords.size() / 2;

    bool all_normals = true, all_uvs = true;
    for (const auto& shape : reader.GetShapes())
        for (const auto& corner : shape.mesh.indices) {
            if (corner.vertex_index < 0 || size_t(corner.vertex_index) >= positions)
                throw Error(name + "face refers to vertex " +
                            std::to_string(corner.vertex_index + 1) + " of " +
                            std::to_string(positions));
            all_normals &= corner.normal_index >= 0 && size_t(corner.normal_index) < normals;
            all_uvs &= corner.texcoord_index >= 0 && size_t(corner.texcoord_index) < uvs;
        }

    Mesh mesh;
    std::unordered_map<tinyobj::index_t, uint32_t, CornerHash, CornerEqual> vertex_of;
    auto vertex = [&](tinyobj::index_t corner) {
        if (!all_normals) corner.normal_index = -1;
        if (!all_uvs) corner.texcoord_index = -1;
        auto [it, inserted] = vertex_of.try_emplace(corner, uint32_t(mesh.positions.size()));
        if (inserted) {
            const float* p = &attrib.vertices[3 * size_t(corner.vertex_index)];
            mesh.positions.emplace_back(p[0], p[1], p[2]);
            if (all_normals) {
                const float* n = &attrib.normals[3 * size_t(corner.normal_index)];
                mesh.normals.emplace_back(n[0], n[1], n[2]);
            }
            if (all_uvs) {
                const float* t = &attrib.texcoords[2 * size_t(corner.texcoord_index)];
                mesh.uvs.emplace_back(t[0], t[1]);
            }
        }
        return it->second;
    };
    for (const auto& shape : reader.GetShapes()) {
        size_t offset = 0;
        for (const unsigned char corners : shape.mesh.num_face_vertices) {
            const tinyobj::index_t* face = &shape.mesh.indices[offset];
            for (unsigned k = 1; k + 1 < corners; ++k) {  // fan from the first corner
                mesh.indices.push_back(vertex(face[0]));
                mesh.indices.push_back(vertex(face[k]));
                mesh.indices.push_back(vertex(face[k + 1]));
            }
            offset += corners;
        }
    }
    if (mesh.indices.empty()) throw Error(name + "no triangles");
    return mesh;
}

Camera load_camera(const std::filesystem::path& path) {
    std::ifstream file(path);
    if (!file) throw Error("cannot read '" + path.string() + "': no such file or not readable");
    Camera camera;
    std::string line;
    for (int number = 1; std::getline(file, line); ++number) {
        std::istringstream words(line);
        std::string key;
        if (!(words >> key) || key[0] == '#') continue;
        auto bad = [&](const std::string& why) {
            return Error("cannot read '" + path.string() + "': line " + std::to_string(number) +
                         ": " + why);
        };
        auto read = [&](float* values, int count) {
            for (int i = 0; i < count; ++i)
                if (!(words >> values[i]) || !std::isfinite(values[i]))
                    throw bad("'" + key + "' expects " + std::to_string(count) + " finite numbers");
            std::string extra;
            if (words >> extra) throw bad("unexpected '" + extra + "' after '" + key + "'");
        };
        if (key == "eye") read(&camera.eye.x, 3);
        else if (key == "lookat") read(&camera.lookat.x, 3);
        else if (key == "up") read(&camera.up.x, 3);
        else if (key == "fovy_deg") read(&camera.fovy_deg, 1);
        else if (key == "near") read(&camera.near, 1);
        else if (key == "far") read(&camera.far, 1);
        else throw bad("unknown key '" + key + "'");
    }
    return camera;
}

}  // namespace tessera::peer
