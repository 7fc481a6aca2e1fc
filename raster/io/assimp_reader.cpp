#include "raster/io/assimp_reader.h"

#include <assimp/GltfMaterial.h>
#include <assimp/Importer.hpp>
#include <assimp/material.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>

#include "raster/core/error.h"

namespace tessera::io {
namespace {

// Post-processing: polygons to triangles (Assimp's ear clipping), meshes split by primitive
// type so that points and lines can be left out, and the validation of every index and count
// (aiProcess_ValidateDataStructure). Broken values (NaN normals or uv) are dealt with later,
// per vertex, rather than by Assimp's FindInvalidData, which drops a whole mesh for one NaN
// position; welding is tessera's too (mesh_weld.h).
constexpr unsigned kPostProcess = aiProcess_Triangulate | aiProcess_SortByPType | aiProcess_ValidateDataStructure;

// Missing normals. glTF 2.0 requires flat normals then: the mesh is left without them and the
// shading kernel uses each triangle's face normal. Other formats (a scanned PLY, an OBJ without
// vn) get smooth normals, averaged over the faces that meet at a position (Assimp's
// GenSmoothNormals), but not across edges sharper than this crease angle, so a cube stays a
// cube.
constexpr float kCreaseDegrees = 80.0f;

std::string lower_extension(const std::filesystem::path& path) {
    std::string ext = path.extension().string();
    for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
    return ext;
}

// Assimp's messages sometimes span lines; ours are one line.
std::string one_line(std::string text) {
    for (char& c : text)
        if (c == '\n' || c == '\r' || c == '\t') c = ' ';
    while (!text.empty() && text.back() == ' ') text.pop_back();
    return text.empty() ? "the file was rejected" : text;
}

glm::mat4 to_glm(const aiMatrix4x4& m) {
    // aiMatrix4x4 is row-major (a1..a4 is the first row, translation in a4, b4, c4).
    return glm::mat4(m.a1, m.b1, m.c1, m.d1, m.a2, m.b2, m.c2, m.d2, m.a3, m.b3, m.c3, m.d3, m.a4, m.b4, m.c4, m.d4);
}

std::string texture_name(const aiMaterial& m, aiTextureType type) {
    aiString path;
    if (m.GetTextureCount(type) == 0 || m.GetTexture(type, 0, &path) != AI_SUCCESS) return {};
    return path.C_Str();
}

// A texture reference as the file writes it: "*N" or a name Assimp matched to an embedded image,
// else a path relative to the model (backslashes from Windows exporters read as separators).
ModelTextureRef texture_ref(const aiScene& scene, const std::filesystem::path& model, const std::string& name) {
    ModelTextureRef ref;
    ref.name = name;
    if (const auto [texture, index] = scene.GetEmbeddedTextureAndIndex(name.c_str()); texture) {
        ref.embedded = index;
        return ref;
    }
    std::string path = name;
    std::replace(path.begin(), path.end(), '\\', '/');
    const std::filesystem::path relative(path);
    const std::filesystem::path folder = model.parent_path();
    ref.file = relative.is_absolute() ? relative : folder / relative;
    // An absolute path from the exporter's machine, or a folder that was not shipped: the
    // file itself beside the model is what the author meant.
    std::error_code ec;
    if (!std::filesystem::exists(ref.file, ec) && relative.has_filename() &&
        std::filesystem::exists(folder / relative.filename(), ec))
        ref.file = folder / relative.filename();
    return ref;
}

ModelMaterial read_material(const aiScene& scene, const aiMaterial& m, const std::filesystem::path& path,
                            std::vector<std::string>& warnings) {
    ModelMaterial out;
    aiString name;
    if (m.Get(AI_MATKEY_NAME, name) == AI_SUCCESS) out.name = name.C_Str();

    aiColor4D base;
    float number = 0.0f;
    aiString mode;
    const bool gltf = m.Get(AI_MATKEY_GLTF_ALPHAMODE, mode) == AI_SUCCESS;
    if (m.Get(AI_MATKEY_BASE_COLOR, base) == AI_SUCCESS) {
        out.base_colour = {base.r, base.g, base.b, base.a};
    } else if (aiColor3D kd; m.Get(AI_MATKEY_COLOR_DIFFUSE, kd) == AI_SUCCESS) {
        out.base_colour = {kd.r, kd.g, kd.b, 1.0f};
        if (m.Get(AI_MATKEY_OPACITY, number) == AI_SUCCESS) out.base_colour.a = number;
    }
    if (gltf || m.Get(AI_MATKEY_METALLIC_FACTOR, number) == AI_SUCCESS) {
        out.workflow = ModelWorkflow::metallic_roughness;
        if (m.Get(AI_MATKEY_METALLIC_FACTOR, number) == AI_SUCCESS) out.metallic = number;
        if (m.Get(AI_MATKEY_ROUGHNESS_FACTOR, number) == AI_SUCCESS) out.roughness = number;
    } else {
        if (aiColor3D ks; m.Get(AI_MATKEY_COLOR_SPECULAR, ks) == AI_SUCCESS) out.specular = {ks.r, ks.g, ks.b};
        if (m.Get(AI_MATKEY_SHININESS, number) == AI_SUCCESS) out.shininess = number;
    }
    if (gltf) {
        const std::string alpha = mode.C_Str();
        out.alpha = alpha == "MASK" ? ModelAlpha::mask : alpha == "BLEND" ? ModelAlpha::blend : ModelAlpha::opaque;
        if (m.Get(AI_MATKEY_GLTF_ALPHACUTOFF, number) == AI_SUCCESS) out.alpha_cutoff = number;
    } else if (out.base_colour.a < 1.0f) {
        out.alpha = ModelAlpha::blend;
    }

    std::string base_name = texture_name(m, aiTextureType_BASE_COLOR);
    aiTextureType base_type = aiTextureType_BASE_COLOR;
    if (base_name.empty()) {
        base_name = texture_name(m, aiTextureType_DIFFUSE);
        base_type = aiTextureType_DIFFUSE;
    }
    if (!base_name.empty()) {
        out.base_colour_texture = texture_ref(scene, path, base_name);
        int wrap = aiTextureMapMode_Wrap;
        if (m.Get(AI_MATKEY_MAPPINGMODE_U(base_type, 0), wrap) == AI_SUCCESS) out.clamp = wrap == aiTextureMapMode_Clamp;
        constexpr int kGlNearest = 0x2600;  // glTF samplers use the OpenGL enums
        int filter = 0;
        if (m.Get(AI_MATKEY_GLTF_MAPPINGFILTER_MAG(base_type, 0), filter) == AI_SUCCESS) out.nearest = filter == kGlNearest;
    }
    if (const std::string normal_name = texture_name(m, aiTextureType_NORMALS); !normal_name.empty())
        out.normal_texture = texture_ref(scene, path, normal_name);
    // Assimp 5.2 files glTF's metallicRoughnessTexture under UNKNOWN (later versions also under
    // METALNESS and DIFFUSE_ROUGHNESS, the same image).
    if (out.workflow == ModelWorkflow::metallic_roughness)
        for (const aiTextureType type : {aiTextureType_UNKNOWN, aiTextureType_METALNESS})
            if (const std::string texture = texture_name(m, type); !texture.empty()) {
                out.metallic_roughness_texture = texture_ref(scene, path, texture);
                break;
            }
    for (const aiTextureType type : {base_type, aiTextureType_NORMALS}) {
        int channel = 0;
        if (m.GetTextureCount(type) > 0 && m.Get(AI_MATKEY_UVWSRC(type, 0), channel) == AI_SUCCESS && channel != 0)
            warnings.push_back("'" + path.string() + "': material '" + out.name + "' samples uv set " +
                               std::to_string(channel) + "; tessera imports uv set 0 and uses it instead");
    }
    return out;
}

ModelImage read_image(const aiTexture& t) {
    ModelImage image;
    image.name = t.mFilename.C_Str();
    if (t.mHeight == 0) {  // an encoded file of mWidth bytes
        image.format.assign(t.achFormatHint, strnlen(t.achFormatHint, sizeof t.achFormatHint));
        const auto* bytes = reinterpret_cast<const uint8_t*>(t.pcData);
        image.encoded.assign(bytes, bytes + t.mWidth);
    } else {  // mWidth x mHeight aiTexel (b, g, r, a)
        image.width = int(t.mWidth);
        image.height = int(t.mHeight);
        const size_t count = size_t(t.mWidth) * t.mHeight;
        image.rgba.resize(count * 4);
        for (size_t i = 0; i < count; ++i) {
            const aiTexel& x = t.pcData[i];
            image.rgba[4 * i] = x.r;
            image.rgba[4 * i + 1] = x.g;
            image.rgba[4 * i + 2] = x.b;
            image.rgba[4 * i + 3] = x.a;
        }
    }
    return image;
}

RawMesh read_mesh(const aiMesh& in) {
    RawMesh out;
    out.name = in.mName.C_Str();
    out.material = in.mMaterialIndex;
    const size_t n = in.mNumVertices;
    const auto copy3 = [n](const aiVector3D* from, std::vector<glm::vec3>& to) {
        if (!from) return;
        to.resize(n);
        for (size_t v = 0; v < n; ++v) to[v] = {from[v].x, from[v].y, from[v].z};
    };
    copy3(in.mVertices, out.positions);
    copy3(in.mNormals, out.normals);
    if (in.mTangents && in.mBitangents && in.mNormals) {
        copy3(in.mTangents, out.tangents);
        copy3(in.mBitangents, out.bitangents);
    }
    if (const aiVector3D* uv = in.mTextureCoords[0]) {
        out.uvs.resize(n);
        for (size_t v = 0; v < n; ++v) out.uvs[v] = {uv[v].x, uv[v].y};
    }
    out.triangles.reserve(size_t(in.mNumFaces) * 3);
    for (unsigned f = 0; f < in.mNumFaces; ++f) {
        const aiFace& face = in.mFaces[f];
        if (face.mNumIndices != 3) {
            ++out.points_and_lines;
            continue;
        }
        out.triangles.insert(out.triangles.end(), face.mIndices, face.mIndices + 3);
    }
    return out;
}

}  // namespace

RawModel read_with_assimp(const std::filesystem::path& path) {
    Assimp::Importer importer;
    importer.SetPropertyFloat(AI_CONFIG_PP_GSN_MAX_SMOOTHING_ANGLE, kCreaseDegrees);
    const std::string ext = lower_extension(path);
    const aiScene* scene = importer.ReadFile(path.string(), kPostProcess);
    if (scene && ext != ".gltf" && ext != ".glb") scene = importer.ApplyPostProcessing(aiProcess_GenSmoothNormals);
    if (!scene) throw Error("Assimp: " + one_line(importer.GetErrorString()));
    if (!scene->mRootNode || scene->mNumMeshes == 0) throw Error("no triangle meshes in the file");

    RawModel model;
    for (unsigned i = 0; i < scene->mNumTextures; ++i) model.images.push_back(read_image(*scene->mTextures[i]));
    for (unsigned i = 0; i < scene->mNumMaterials; ++i)
        model.materials.push_back(read_material(*scene, *scene->mMaterials[i], path, model.warnings));
    for (unsigned i = 0; i < scene->mNumMeshes; ++i) model.meshes.push_back(read_mesh(*scene->mMeshes[i]));
    // The node tree, depth first, without recursion (a deep tree must not exhaust the stack);
    // children are pushed in reverse so that they come out in order.
    std::vector<std::pair<const aiNode*, int32_t>> stack{{scene->mRootNode, -1}};
    while (!stack.empty()) {
        const auto [node, parent] = stack.back();
        stack.pop_back();
        RawNode raw;
        raw.name = node->mName.C_Str();
        raw.parent = parent;
        raw.transform = to_glm(node->mTransformation);
        raw.meshes.assign(node->mMeshes, node->mMeshes + node->mNumMeshes);
        model.nodes.push_back(std::move(raw));
        const int32_t self = int32_t(model.nodes.size() - 1);
        for (unsigned c = node->mNumChildren; c-- > 0;)
            if (node->mChildren[c]) stack.push_back({node->mChildren[c], self});
    }
    return model;
}

bool assimp_reads_extension(const std::string& extension) {
    if (extension.size() < 2) return false;
    static const Assimp::Importer importer;
    return importer.IsExtensionSupported(extension.c_str());
}

}  // namespace tessera::io
