// The model importer (issue 18): io::read_model (Assimp, node transforms, welding, the
// declared-size check), the material mapping and texture loading of asset::import_model,
// and framing.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "raster/asset/framing.h"
#include "raster/asset/model_import.h"
#include "raster/core/error.h"
#include "raster/io/image_io.h"
#include "raster/io/mesh_weld.h"
#include "raster/io/model_file.h"

namespace tessera {
namespace {

namespace fs = std::filesystem;

class ModelFiles : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = fs::temp_directory_path() / ("tessera_model_" + std::to_string(::getpid()) + "_" +
                                            ::testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::create_directories(dir_);
    }
    void TearDown() override { fs::remove_all(dir_); }
    fs::path write(const std::string& name, const std::string& bytes) {
        std::ofstream(dir_ / name, std::ios::binary) << bytes;
        return dir_ / name;
    }
    fs::path dir_;
};

std::string base64(const std::string& bytes) {
    static const char* k = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    for (size_t i = 0; i < bytes.size(); i += 3) {
        uint32_t v = uint32_t(uint8_t(bytes[i])) << 16;
        if (i + 1 < bytes.size()) v |= uint32_t(uint8_t(bytes[i + 1])) << 8;
        if (i + 2 < bytes.size()) v |= uint8_t(bytes[i + 2]);
        out += k[v >> 18 & 63];
        out += k[v >> 12 & 63];
        out += i + 1 < bytes.size() ? k[v >> 6 & 63] : '=';
        out += i + 2 < bytes.size() ? k[v & 63] : '=';
    }
    return out;
}

template <class T>
std::string raw(std::initializer_list<T> values) {
    std::string out(values.size() * sizeof(T), '\0');
    std::memcpy(out.data(), std::data(values), out.size());
    return out;
}

// One triangle (0,0,0) (1,0,0) (0,1,0), normal +z, drawn by a node with `node` (JSON members)
// under a root node with `root`; `material` is the glTF material object.
std::string triangle_gltf(const std::string& root, const std::string& node, const std::string& material) {
    const std::string buffer = raw<float>({0, 0, 0, 1, 0, 0, 0, 1, 0}) + raw<float>({0, 0, 1, 0, 0, 1, 0, 0, 1});
    return R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
      "nodes": [{"children": [1])" + root + R"(}, {"mesh": 0)" + node + R"(}],
      "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1}, "material": 0}]}],
      "materials": [)" + material + R"(],
      "buffers": [{"byteLength": 72, "uri": "data:application/octet-stream;base64,)" + base64(buffer) + R"("}],
      "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36, "byteLength": 36}],
      "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]},
                    {"bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC3"}]})";
}

TEST_F(ModelFiles, GltfNodeTransformsComposeAndMirroringKeepsFrontFaces) {
    // Root: translate (10, 0, 0); child: mirror x (scale -1, 2, 1). Corner (1, 0, 0) -> (9, 0, 0).
    const fs::path path = write("t.gltf", triangle_gltf(R"(, "translation": [10, 0, 0])", R"(, "scale": [-1, 2, 1])",
                                                        R"({"name": "m"})"));
    const io::ModelFile model = io::read_model(path);
    ASSERT_EQ(model.parts.size(), 1u);
    const Mesh& m = model.parts[0].mesh;
    ASSERT_EQ(m.triangle_count(), 1u);
    const glm::vec3 a = m.positions[m.indices[0]], b = m.positions[m.indices[1]], c = m.positions[m.indices[2]];
    EXPECT_EQ(model.lower, glm::vec3(9, 0, 0));
    EXPECT_EQ(model.upper, glm::vec3(10, 2, 0));
    // The mirrored triangle still faces its (transformed) normal: counter-clockwise seen from +z.
    EXPECT_GT(glm::cross(b - a, c - a).z, 0.0f);
    for (const glm::vec3& n : m.normals) EXPECT_NEAR(n.z, 1.0f, 1e-6f);
}

TEST_F(ModelFiles, GltfMaterialsMapOntoBlinnPhong) {
    const fs::path path = write("m.gltf", triangle_gltf("", "", R"({"name": "gold", "alphaMode": "MASK",
        "alphaCutoff": 0.25, "pbrMetallicRoughness": {"baseColorFactor": [1, 0.8, 0.2, 0.9],
        "metallicFactor": 1, "roughnessFactor": 0.5}})"));
    const io::ModelFile model = io::read_model(path);
    ASSERT_EQ(model.parts.size(), 1u);
    const io::ModelMaterial& m = model.materials.at(model.parts[0].material);
    EXPECT_EQ(m.name, "gold");
    EXPECT_EQ(m.workflow, io::ModelWorkflow::metallic_roughness);
    EXPECT_EQ(m.alpha, io::ModelAlpha::mask);
    EXPECT_FLOAT_EQ(m.alpha_cutoff, 0.25f);
    const scene::Material mapped = asset::map_material(m);
    EXPECT_EQ(mapped.kd, glm::vec3(0.0f));  // a metal reflects no diffuse light
    EXPECT_NEAR(mapped.ks.g, 0.8f, 1e-6f);   // its specular colour is its base colour
    EXPECT_NEAR(mapped.shine, 2.0f / 0.0625f - 2.0f, 1e-3f);  // alpha = roughness^2 = 0.25
    EXPECT_FLOAT_EQ(mapped.alpha_cutoff, 0.25f);
    EXPECT_FLOAT_EQ(mapped.opacity, 0.9f);
    EXPECT_TRUE(mapped.masked());
    EXPECT_FALSE(mapped.transparent());
}

TEST_F(ModelFiles, ObjMaterialsTexturesAndAMissingTextureWarning) {
    const std::vector<uint8_t> texels = {255, 0, 0, 0, 255, 0, 0, 0, 255, 255, 255, 255};
    io::write_image(dir_ / "t.png", io::ImageView{2, 2, 3, io::PixelType::u8, texels.data()});
    write("a.mtl", "newmtl shiny\nKd 0.5 0.25 0.125\nKs 0.2 0.2 0.2\nNs 40\nmap_Kd t.png\n"
                   "newmtl lost\nKd 1 1 1\nd 0.5\nmap_Kd C:\\\\exporter\\\\gone.png\n");
    const fs::path path = write("a.obj", "mtllib a.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\n"
                                         "usemtl shiny\nf 1/1 2/2 3/3\nusemtl lost\nf 1/1 3/3 4/2\n");
    const asset::ImportedModel model = asset::import_model(path);
    ASSERT_EQ(model.objects.size(), 2u);
    ASSERT_EQ(model.warnings.size(), 1u);
    EXPECT_NE(model.warnings[0].find("'lost'"), std::string::npos) << model.warnings[0];
    EXPECT_NE(model.warnings[0].find("gone.png"), std::string::npos) << model.warnings[0];
    ASSERT_EQ(model.textures.size(), 1u);
    const scene::Material& shiny = model.materials[model.objects[0].material];
    EXPECT_EQ(shiny.kd, glm::vec3(0.5f, 0.25f, 0.125f));
    EXPECT_EQ(shiny.ka, shiny.kd);
    EXPECT_FLOAT_EQ(shiny.shine, 40.0f);
    EXPECT_EQ(shiny.diffuse_texture, 0);
    const scene::Material& lost = model.materials[model.objects[1].material];
    EXPECT_EQ(lost.diffuse_texture, scene::kNoTexture);
    EXPECT_TRUE(lost.transparent());
    EXPECT_FLOAT_EQ(lost.opacity, 0.5f);
}

TEST_F(ModelFiles, PlyWithoutNormalsGetsSmoothOnesAndFaceCornersAreWelded) {
    // Two triangles of a tent, meeting at 90 degrees: under the crease angle, so smooth.
    const fs::path path = write("t.ply", "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
                                         "property float z\nelement face 2\nproperty list uchar int vertex_indices\n"
                                         "end_header\n0 0 0\n1 0 0\n0 1 1\n0 -1 1\n3 0 1 2\n3 1 0 3\n");
    const io::ModelFile model = io::read_model(path);
    ASSERT_EQ(model.parts.size(), 1u);
    const Mesh& m = model.parts[0].mesh;
    EXPECT_EQ(m.triangle_count(), 2u);
    EXPECT_EQ(m.vertex_count(), 4u);  // the shared edge's corners welded
    ASSERT_EQ(m.normals.size(), 4u);
    for (const glm::vec3& n : m.normals) EXPECT_NEAR(glm::length(n), 1.0f, 1e-5f);
}

TEST_F(ModelFiles, BadFilesAreOneLineErrorsNamingTheFile) {
    const auto message = [&](const fs::path& path) {
        try {
            io::read_model(path);
        } catch (const Error& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    const std::string huge = message(write("h.ply", "ply\nformat ascii 1.0\nelement vertex 353535235358\n"
                                                    "property float x\nend_header\n0\n"));
    EXPECT_NE(huge.find("h.ply': the PLY header declares 353535235358 'vertex'"), std::string::npos) << huge;
    const std::string missing = message(dir_ / "nope.glb");
    EXPECT_NE(missing.find("nope.glb': no such file"), std::string::npos) << missing;
    const std::string lines = message(write("l.obj", "v 0 0 0\nv 1 0 0\nl 1 2\n"));
    EXPECT_NE(lines.find("no triangles"), std::string::npos) << lines;
    const std::string nan = message(write("n.obj", "v nan 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"));
    EXPECT_NE(nan.find("NaN"), std::string::npos) << nan;
    const std::string unknown = message(write("x.xyz123", "hello"));
    EXPECT_NE(unknown.find("no model reader"), std::string::npos) << unknown;
    for (const std::string& m : {huge, missing, lines, nan, unknown}) EXPECT_EQ(m.find('\n'), std::string::npos) << m;
}

TEST(MeshWeld, MergesIdenticalCornersKeepsFirstOrderAndSeams) {
    Mesh m;
    m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 0, 0}, {0, 1, 0}, {-0.0f, 0, 0}, {0, 0, 0}};
    m.uvs = {{0, 0}, {1, 0}, {0, 1}, {1, 0}, {0, 1}, {0, 0}, {0.5f, 0}};
    m.indices = {0, 1, 2, 3, 4, 5, 6, 1, 2};
    EXPECT_EQ(io::weld_vertices(m), 2u);
    // (1,0,0) and (0,1,0) merged; -0 is not +0, a different uv is a seam: both stay.
    EXPECT_EQ(m.positions.size(), 5u);
    EXPECT_EQ(m.indices, (std::vector<uint32_t>{0, 1, 2, 1, 2, 3, 4, 1, 2}));
    EXPECT_EQ(m.uvs[4], glm::vec2(0.5f, 0));
}

TEST(Framing, TheWholeBoxIsInViewAndBetweenTheClipPlanes) {
    for (const float aspect : {0.5f, 1.0f, 16.0f / 9.0f, 4.0f}) {
        const glm::vec3 lower(-3, 10, 100), upper(5, 11, 140);
        const Camera camera = asset::frame_box(lower, upper, aspect);
        const glm::mat4 vp = camera.view_projection();
        for (int corner = 0; corner < 8; ++corner) {
            const glm::vec3 p(corner & 1 ? upper.x : lower.x, corner & 2 ? upper.y : lower.y, corner & 4 ? upper.z : lower.z);
            const glm::vec4 clip = vp * glm::vec4(p, 1.0f);
            ASSERT_GT(clip.w, 0.0f);
            for (int k = 0; k < 3; ++k) {
                EXPECT_LE(std::abs(clip[k]), clip.w) << "corner " << corner << " axis " << k << " aspect " << aspect;
            }
        }
    }
    // A single point is framed too (a tiny sphere around it).
    const Camera point = asset::frame_box(glm::vec3(2), glm::vec3(2), 1.0f);
    EXPECT_GT(point.near, 0.0f);
    EXPECT_GT(point.far, point.near);
}

TEST(Framing, PrintedFlagsReadBackToTheSameFloats) {
    const Camera c = asset::frame_box(glm::vec3(-0.1f, 0.2f, 0.3f), glm::vec3(1.7f, 2.9f, 0.31f), 1.5f);
    const std::string flags = asset::camera_flags(c);
    Camera back;
    ASSERT_EQ(std::sscanf(flags.c_str(), "--eye %f,%f,%f --lookat %f,%f,%f --up %f,%f,%f --fov %f --near %f --far %f",
                          &back.eye.x, &back.eye.y, &back.eye.z, &back.lookat.x, &back.lookat.y, &back.lookat.z,
                          &back.up.x, &back.up.y, &back.up.z, &back.fovy_deg, &back.near, &back.far),
              12)
        << flags;
    EXPECT_EQ(back.eye, c.eye);
    EXPECT_EQ(back.lookat, c.lookat);
    EXPECT_EQ(back.near, c.near);
    EXPECT_EQ(back.far, c.far);
}

}  // namespace
}  // namespace tessera
