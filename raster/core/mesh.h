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

// A range of a mesh that moves as one (an object of a baked scene): triangles
// [first_triangle, first_triangle + triangle_count), whose indices all lie in
// [first_vertex, first_vertex + vertex_count). `still`: the part is the same in every frame
// (its object is not animated), so work spent on it once serves the whole animation.
struct MeshPart {
    size_t first_vertex = 0, vertex_count = 0;
    size_t first_triangle = 0, triangle_count = 0;
    bool still = false;
};

}  // namespace tessera
