// The triangle mesh every path shares: the rasterizer, the Embree ray tracer and the shading
// code read the same buffers, so the two renderers are compared on identical work.
//
// Structure of arrays: one stream per attribute, indexed by vertex; `indices` holds three
// vertex indices per triangle, and a triangle's id is its position in that list (the order
// of submission, which the rasterizer keeps for blending and for --out-id).
#pragma once
#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

namespace tessera {

struct Mesh {
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> normals;   // empty, or one per position
    std::vector<glm::vec2> uvs;       // empty, or one per position
    std::vector<glm::vec4> tangents;  // empty, or one per position (xyz, w = bitangent sign)
    std::vector<uint32_t> indices;    // 3 per triangle

    size_t vertex_count() const { return positions.size(); }
    size_t triangle_count() const { return indices.size() / 3; }
};

}  // namespace tessera
