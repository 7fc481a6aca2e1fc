// A model file as Assimp read it, before tessera's conversion (model_file.h): the node tree
// flattened in depth-first order, the triangle meshes' raw arrays, the materials as the file
// states them and the embedded images. Plain data with a byte form, because the reading
// happens in a child process (isolated_call.h) and the result must cross a pipe.
#pragma once
#include <glm/glm.hpp>

#include <cstdint>
#include <string>
#include <vector>

#include "raster/io/model_file.h"

namespace tessera::io {

struct RawNode {
    std::string name;
    int32_t parent = -1;        // index of an earlier node, -1 for the root
    glm::mat4 transform{1.0f};  // relative to the parent
    std::vector<uint32_t> meshes;
};

struct RawMesh {
    std::string name;
    uint32_t material = 0;
    std::vector<glm::vec3> positions, normals, tangents, bitangents;  // normals.. empty or one per position
    std::vector<glm::vec2> uvs;                                      // uv set 0
    std::vector<uint32_t> triangles;                                 // 3 indices per triangle
    uint64_t points_and_lines = 0;                                   // faces left out
};

struct RawModel {
    std::vector<RawNode> nodes;
    std::vector<RawMesh> meshes;
    std::vector<ModelMaterial> materials;
    std::vector<ModelImage> images;
    std::vector<std::string> warnings;
};

std::vector<uint8_t> to_bytes(const RawModel& model);
// Throws tessera::Error ("truncated" or "corrupt") when `bytes` is not what to_bytes wrote.
RawModel raw_model_from_bytes(const std::vector<uint8_t>& bytes);

}  // namespace tessera::io
