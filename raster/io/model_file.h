// 3-D model files through Assimp (Debian libassimp-dev): glTF 2.0 (.gltf, .glb), Wavefront OBJ
// with its MTL materials, PLY, STL, FBX, Collada and the other formats Assimp reads.
//
// What comes out is plain data, ready for the scene layer to map onto tessera's materials:
// - parts: one triangle mesh per (node, mesh) pair of the file's node tree, in depth-first node
//   order, with the node's accumulated transform applied (normals by its inverse transpose, the
//   winding reversed under a mirroring transform, so front faces stay counter-clockwise);
//   polygons triangulated, points and lines left out, normals generated (smooth, as Assimp's
//   GenSmoothNormals) where the file has none, uv set 0, tangents when the file has them;
//   identical corners welded (exact bits), so a face-indexed OBJ or PLY becomes an indexed mesh;
// - materials as the file states them (base colour factor and texture, normal map, alpha mode,
//   Phong or metallic-roughness parameters), each texture a resolved file or an embedded image.
//
// Bad input: a missing or unreadable file, a format Assimp does not read, a file it rejects
// (Assimp's own validation, aiProcess_ValidateDataStructure, runs on every import), a file whose
// header declares more elements than its size can hold, or one with no triangles is a
// tessera::Error with one line naming the file ("cannot read 'x.glb': ..."). Vertices with NaN,
// infinite or huge coordinates (beyond kMaxModelCoordinate after the node transform) are left
// out with every triangle that uses them, and counted.
#pragma once
#include <glm/glm.hpp>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "raster/core/mesh.h"

namespace tessera::io {

inline constexpr float kMaxModelCoordinate = 1e18f;

// Where a material's texture comes from: a file beside the model, or an image stored inside it.
struct ModelTextureRef {
    std::string name;            // as the model file writes it (for messages)
    std::filesystem::path file;  // resolved path (may not exist: the caller warns); empty when embedded
    int embedded = -1;           // index into ModelFile::images
};

// glTF 2.0's alphaMode; other formats: blend when their opacity is below 1.
enum class ModelAlpha : uint8_t { opaque, mask, blend };
// How the file parameterises its surfaces: Phong (OBJ's MTL and most older formats) or glTF's
// metallic-roughness.
enum class ModelWorkflow : uint8_t { phong, metallic_roughness };

struct ModelMaterial {
    std::string name;
    ModelWorkflow workflow = ModelWorkflow::phong;
    glm::vec4 base_colour{1.0f};  // linear RGB and alpha: glTF baseColorFactor; MTL Kd and d
    glm::vec3 specular{0.0f};     // MTL Ks
    float shininess = 0.0f;       // MTL Ns
    float metallic = 1.0f;        // glTF metallicFactor
    float roughness = 1.0f;       // glTF roughnessFactor
    ModelAlpha alpha = ModelAlpha::opaque;
    float alpha_cutoff = 0.5f;    // glTF alphaCutoff (mask)
    bool clamp = false;           // the base colour texture's sampler clamps instead of repeating
    bool nearest = false;         // ... and magnifies with nearest texels (glTF magFilter NEAREST)
    std::optional<ModelTextureRef> base_colour_texture;
    std::optional<ModelTextureRef> normal_texture;
    std::optional<ModelTextureRef> metallic_roughness_texture;  // glTF: roughness in G, metallic in B
};

// An image stored inside the model (a .glb buffer, a data URI, an FBX blob): either the bytes
// of an encoded file (PNG, JPEG...: `encoded`) or raw 8-bit RGBA texels, rows top to bottom.
struct ModelImage {
    std::string name;
    std::string format;  // of `encoded`: a file extension ("png", "jpg"), possibly empty
    std::vector<uint8_t> encoded;
    int width = 0, height = 0;
    std::vector<uint8_t> rgba;
};

struct ModelPart {
    std::string name;  // node name, then mesh name
    Mesh mesh;         // in the model's space (node transforms applied)
    uint32_t material = 0;
};

struct ModelStats {
    size_t triangles = 0;          // kept
    size_t vertices = 0;           // kept, after welding
    size_t skipped_triangles = 0;  // left out: a corner with a NaN, infinite or huge coordinate
    size_t skipped_primitives = 0; // points and lines
    double read_ms = 0.0;          // Assimp's import and post-processing
    double convert_ms = 0.0;       // node transforms, welding, materials
};

struct ModelFile {
    std::filesystem::path path;
    std::vector<ModelPart> parts;
    std::vector<ModelMaterial> materials;
    std::vector<ModelImage> images;
    glm::vec3 lower{0.0f}, upper{0.0f};  // bounds of every kept vertex
    std::vector<std::string> warnings;   // one line each, naming the file
    ModelStats stats;
};

// Throws tessera::Error naming `path` and what is wrong.
ModelFile read_model(const std::filesystem::path& path);

// True when Assimp reads files with this extension (".glb", ".PLY": any case, with the dot).
bool model_format_supported(const std::filesystem::path& path);

// Every part's mesh concatenated in order, into one mesh (triangle ids follow the parts).
Mesh merge_parts(const ModelFile& model);

}  // namespace tessera::io
