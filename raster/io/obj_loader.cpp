#include "raster/io/obj_loader.h"

#include <tiny_obj_loader.h>

#include <charconv>
#include <cstdio>
#include <cstring>
#include <string_view>
#include <tuple>
#include <cmath>
#include <unordered_map>

#include "raster/core/atomic_file.h"
#include "raster/core/error.h"
#include "raster/core/input_file.h"

namespace tessera::io {

namespace {

[[noreturn]] void fail(const std::string& name, const std::string& what) {
    throw Error("cannot read '" + name + "': " + what);
}

bool good(double v) { return std::isfinite(v) && std::fabs(v) <= kMaxObjCoordinate; }

// tinyobjloader reads unparsable numbers (and "nan", "inf") as 0 and drops faces with fewer
// than three corners without a word; check those records ourselves first so that a malformed
// file is reported with its line. Returns, per "v" record in file order, whether it is bad
// (NaN, infinite or huge).
// OBJ is text: a NUL byte means binary data (a wrong file, or a corrupt one), which would
// otherwise read as an empty mesh since unknown records are skipped (issue 10).
void check_text(std::string_view text, const std::string& name) {
    if (const size_t nul = text.find('\0'); nul != std::string::npos)
        fail(name, "not an OBJ text file (binary data at byte " + std::to_string(nul) + ")");
}

std::vector<uint8_t> check_records(const std::string& text, const std::string& name) {
    check_text(text, name);
    std::vector<uint8_t> bad_positions;
    const char* p = text.data();
    const char* const end = p + text.size();
    auto blank = [](char c) { return c == ' ' || c == '\t' || c == '\r'; };
    for (size_t number = 1; p < end; ++number) {
        const char* eol = static_cast<const char*>(std::memchr(p, '\n', size_t(end - p)));
        if (!eol) eol = end;
        // Tokens of this line, up to a comment.
        auto next = [&](std::string_view& token) {
            while (p < eol && blank(*p)) ++p;
            if (p == eol || *p == '#') return false;
            const char* start = p;
            while (p < eol && !blank(*p)) ++p;
            token = std::string_view(start, size_t(p - start));
            return true;
        };
        const auto where = [&] { return "line " + std::to_string(number) + ": "; };
        std::string_view keyword, token;
        if (next(keyword)) {
            if (keyword == "f") {
                size_t corners = 0;
                while (next(token)) ++corners;
                if (corners < 3)
                    fail(name, where() + "a face needs at least 3 vertices, found " + std::to_string(corners));
            } else if (keyword == "v" || keyword == "vn" || keyword == "vt") {
                const size_t need = keyword == "vt" ? 1 : 3;
                size_t count = 0;
                bool bad = false;
                while (next(token)) {
                    double value;
                    auto [ptr, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
                    if (ptr != token.data() + token.size() ||
                        (ec != std::errc() && ec != std::errc::result_out_of_range))
                        fail(name, where() + "'" + std::string(token) + "' is not a number");
                    if (count < 3) bad |= ec == std::errc::result_out_of_range || !good(value);
                    ++count;
                }
                if (count < need)
                    fail(name, where() + "expected " + std::to_string(need) + " numbers, found " + std::to_string(count));
                if (keyword == "v") bad_positions.push_back(bad);
            }
        }
        p = eol + 1;
    }
    return bad_positions;
}

std::string first_line(std::string text) {
    while (!text.empty() && (text.back() == '\n' || text.back() == '\r')) text.pop_back();
    const size_t newline = text.find('\n');
    return newline == std::string::npos ? text : text.substr(0, newline);
}

}  // namespace

Mesh parse_obj(const std::string& text, const std::string& name, ObjLoadStats* stats) {
    if (text.find('\0') != std::string::npos) fail(name, "binary data, not an OBJ text file");
    const std::vector<uint8_t> bad_records = check_records(text, name);
    tinyobj::ObjReaderConfig config;
    config.triangulate = false;  // fan from the first vertex ourselves (the documented order)
    config.vertex_color = false;
    tinyobj::ObjReader reader;
    if (!reader.ParseFromString(text, "", config))
        fail(name, first_line(reader.Error().empty() ? "malformed OBJ" : reader.Error()));
    const tinyobj::attrib_t& attrib = reader.GetAttrib();
    const size_t positions = attrib.vertices.size() / 3;
    const size_t normals = attrib.normals.size() / 3;
    const size_t texcoords = attrib.texcoords.size() / 2;

    ObjLoadStats s;
    // Bad positions: replaced by the origin, their triangles made degenerate.
    std::vector<uint8_t> bad(positions, 0);
    for (size_t i = 0; i < positions; ++i)
        if ((i < bad_records.size() && bad_records[i]) || !good(attrib.vertices[3 * i]) ||
            !good(attrib.vertices[3 * i + 1]) || !good(attrib.vertices[3 * i + 2])) {
            bad[i] = 1;
            ++s.bad_vertices;
        }

    // One mesh vertex per distinct (position, normal, uv) corner.
    bool any_normal = false, any_uv = false;
    for (const tinyobj::shape_t& shape : reader.GetShapes())
        for (const tinyobj::index_t& index : shape.mesh.indices) {
            any_normal |= index.normal_index >= 0;
            any_uv |= index.texcoord_index >= 0;
        }
    const bool with_normals = any_normal;  // faces without vn get their face normal (below)
    Mesh mesh;
    struct KeyHash {
        size_t operator()(const std::tuple<int, int, int, size_t>& k) const {
            return std::hash<uint64_t>()((uint64_t(uint32_t(std::get<0>(k))) << 32) ^
                                         (uint64_t(uint32_t(std::get<1>(k))) << 16) ^ uint32_t(std::get<2>(k)) ^
                                         (std::get<3>(k) << 40));
        }
    };
    std::unordered_map<std::tuple<int, int, int, size_t>, uint32_t, KeyHash> corners;
    size_t face_number = 0;
    for (const tinyobj::shape_t& shape : reader.GetShapes()) {
        size_t offset = 0;
        for (const unsigned char arity : shape.mesh.num_face_vertices) {
            ++face_number;
            ++s.faces;
            if (arity < 3) fail(name, "face " + std::to_string(face_number) + " has fewer than 3 vertices");
            if (offset + arity > shape.mesh.indices.size()) fail(name, "truncated face list");
            // A face without vn takes its geometric normal (first three corners).
            glm::vec3 face_normal(0.0f, 0.0f, 1.0f);
            bool face_has_normals = true;
            uint32_t corner[256];
            for (unsigned k = 0; k < arity; ++k) {
                const tinyobj::index_t& index = shape.mesh.indices[offset + k];
                if (index.vertex_index < 0 || size_t(index.vertex_index) >= positions)
                    fail(name, "face " + std::to_string(face_number) + ": vertex index out of range");
                if (index.normal_index >= 0 && size_t(index.normal_index) >= normals)
                    fail(name, "face " + std::to_string(face_number) + ": normal index out of range");
                if (index.texcoord_index >= 0 && size_t(index.texcoord_index) >= texcoords)
                    fail(name, "face " + std::to_string(face_number) + ": texture index out of range");
                face_has_normals &= index.normal_index >= 0;
            }
            if (with_normals && !face_has_normals) {
                auto p = [&](unsigned k) {
                    const int v = shape.mesh.indices[offset + k].vertex_index;
                    return glm::vec3(attrib.vertices[3 * v], attrib.vertices[3 * v + 1], attrib.vertices[3 * v + 2]);
                };
                const glm::vec3 n = glm::cross(p(1) - p(0), p(2) - p(0));
                const float length = glm::length(n);
                if (std::isfinite(length) && length > 0.0f) face_normal = n / length;
            }
            for (unsigned k = 0; k < arity; ++k) {
                const tinyobj::index_t& index = shape.mesh.indices[offset + k];
                // Corners with their own normal are shared; face-normal corners are per face.
                const bool own_normal = !with_normals || index.normal_index >= 0;
                const auto key = std::make_tuple(index.vertex_index, index.normal_index, index.texcoord_index,
                                                 own_normal ? size_t(0) : face_number);
                auto [it, inserted] = corners.try_emplace(key, uint32_t(mesh.positions.size()));
                if (inserted) {
                    const int v = index.vertex_index;
                    mesh.positions.push_back(bad[v] ? glm::vec3(0.0f)
                                                    : glm::vec3(attrib.vertices[3 * v], attrib.vertices[3 * v + 1],
                                                                attrib.vertices[3 * v + 2]));
                    if (with_normals) {
                        const int n = index.normal_index;
                        mesh.normals.push_back(n >= 0 ? glm::vec3(attrib.normals[3 * n], attrib.normals[3 * n + 1],
                                                                  attrib.normals[3 * n + 2])
                                                      : face_normal);
                    }
                    if (any_uv) {
                        const int t = index.texcoord_index;
                        mesh.uvs.push_back(t >= 0 ? glm::vec2(attrib.texcoords[2 * t], attrib.texcoords[2 * t + 1])
                                                  : glm::vec2(0.0f));
                    }
                }
                corner[k] = it->second;
            }
            // Fan from the first vertex: (0, k, k + 1).
            for (unsigned k = 1; k + 1 < arity; ++k) {
                const int v0 = shape.mesh.indices[offset].vertex_index;
                const int v1 = shape.mesh.indices[offset + k].vertex_index;
                const int v2 = shape.mesh.indices[offset + k + 1].vertex_index;
                ++s.triangles;
                if (bad[v0] || bad[v1] || bad[v2]) {
                    ++s.skipped_triangles;
                    mesh.indices.insert(mesh.indices.end(), {corner[0], corner[0], corner[0]});
                } else {
                    mesh.indices.insert(mesh.indices.end(), {corner[0], corner[k], corner[k + 1]});
                }
            }
            offset += arity;
        }
    }
    if (stats) *stats = s;
    return mesh;
}

Mesh load_obj(const std::filesystem::path& path, ObjLoadStats* stats) {
    InputFile file(path);  // a device, FIFO or directory is refused at once
    // The first 64 KiB are checked before the rest is read, so that a binary file of
    // gigabytes (or a sparse one of zeros) is refused at once.
    std::string text = file.read(size_t(1) << 16);
    check_text(text, path.string());
    text += file.read_rest();
    return parse_obj(text, path.string(), stats);
}

void write_obj(const std::filesystem::path& path, const Mesh& mesh) {
    std::string out;
    out.reserve(mesh.positions.size() * 40 + mesh.indices.size() * 12);
    char line[160];
    for (const glm::vec3& p : mesh.positions) {
        std::snprintf(line, sizeof line, "v %.9g %.9g %.9g\n", p.x, p.y, p.z);
        out += line;
    }
    for (const glm::vec3& n : mesh.normals) {
        std::snprintf(line, sizeof line, "vn %.9g %.9g %.9g\n", n.x, n.y, n.z);
        out += line;
    }
    for (const glm::vec2& t : mesh.uvs) {
        std::snprintf(line, sizeof line, "vt %.9g %.9g\n", t.x, t.y);
        out += line;
    }
    const bool n = !mesh.normals.empty(), t = !mesh.uvs.empty();
    for (size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
        out += 'f';
        for (int k = 0; k < 3; ++k) {
            const uint32_t v = mesh.indices[i + k] + 1;
            if (n && t) std::snprintf(line, sizeof line, " %u/%u/%u", v, v, v);
            else if (n) std::snprintf(line, sizeof line, " %u//%u", v, v);
            else if (t) std::snprintf(line, sizeof line, " %u/%u", v, v);
            else std::snprintf(line, sizeof line, " %u", v);
            out += line;
        }
        out += '\n';
    }
    write_file_atomically(path, out);
}

}  // namespace tessera::io
