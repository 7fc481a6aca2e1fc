// The SIMD shading pass (stamp_shading.h) against the scalar reference (reference_shading.h):
// bit-identical for id, depth and normal; for phong within one 8-bit level per channel, on a
// tiny fraction of the channels (bound in stamp_shading.h), on a meshed sphere with normals
// and uv and on one with face normals; reading the tiles' stamps and the frame's rows.
#include <gtest/gtest.h>

#include <cstdlib>

#include "raster/pipeline/rasterizer.h"
#include "raster/shade/reference_shading.h"
#include "raster/shade/stamp_shading.h"
#include "raster/workloads/test_meshes.h"

namespace tessera {
namespace {

constexpr int kWidth = 333, kHeight = 201;  // not a multiple of the tile or the lanes

Camera sphere_camera() {
    Camera camera;
    camera.eye = {0.4f, 0.9f, 2.6f};
    camera.lookat = {0.0f, 0.1f, 0.0f};
    camera.aspect = float(kWidth) / float(kHeight);
    return camera;
}

// The SIMD pass reads the tile buffers in their stamp layout (stamps) or the frame's rows.
enum class Path { reference, rows, stamps };

std::vector<uint32_t> shade(const Mesh& mesh, shade::ShadeMode mode, Path path) {
    const Camera camera = sphere_camera();
    std::vector<uint32_t> rgba8(size_t(kWidth) * kHeight, 7);
    const pipeline::TilePass pass = path != Path::reference ? shade::make_stamp_shading_pass(mode, camera, rgba8)
                                                            : shade::make_reference_shading_pass(mode, camera, rgba8);
    pipeline::RasterOptions options;
    options.tile_size = 64;
    options.tile_color = path == Path::reference;
    options.frame_visibility = path != Path::stamps;
    VisibilityBuffer vis;
    pipeline::Rasterizer().render(mesh, camera.view_projection(), pipeline::Viewport(kWidth, kHeight), options, vis, {&pass, 1});
    return rgba8;
}

struct Difference {
    size_t channels = 0, lit = 0;
    int max = 0;
};

Difference compare(const Mesh& mesh, shade::ShadeMode mode, Path path) {
    const std::vector<uint32_t> reference = shade(mesh, mode, Path::reference);
    const std::vector<uint32_t> fast = shade(mesh, mode, path);
    Difference d;
    for (size_t i = 0; i < reference.size(); ++i)
        for (int c = 0; c < 4; ++c) {
            const int r = int(reference[i] >> (8 * c) & 255), f = int(fast[i] >> (8 * c) & 255);
            d.channels += r != f;
            d.max = std::max(d.max, std::abs(r - f));
            d.lit += c < 3 && r != 0;
        }
    return d;
}

Mesh face_normal_sphere() {
    Mesh mesh = workloads::sphere(40, 24);
    mesh.normals.clear();
    mesh.uvs.clear();
    return mesh;
}

TEST(StampShading, IdDepthNormalBitIdentical) {
    for (Path path : {Path::rows, Path::stamps})
        for (const Mesh& mesh : {workloads::sphere(200, 120), face_normal_sphere()})
            for (shade::ShadeMode mode : {shade::ShadeMode::id, shade::ShadeMode::depth, shade::ShadeMode::normal}) {
                const Difference d = compare(mesh, mode, path);
                EXPECT_EQ(d.channels, 0u) << int(mode) << " " << int(path);
                EXPECT_GT(d.lit, size_t(kWidth) * kHeight / 4) << int(mode);  // the sphere is on screen
            }
}

TEST(StampShading, PhongWithinOneLevel) {
    for (Path path : {Path::rows, Path::stamps})
        for (const Mesh& mesh : {workloads::sphere(200, 120), face_normal_sphere()}) {
            const Difference d = compare(mesh, shade::ShadeMode::phong, path);
            EXPECT_LE(d.max, 1) << int(path);
            EXPECT_LE(d.channels, d.lit / 1000) << int(path);  // rounding-boundary cases only
            EXPECT_GT(d.lit, size_t(kWidth) * kHeight / 4);
        }
}

// The id shader's channels are the bytes of id_colour: the SIMD pass packs them unchanged,
// which is exact because quantising a level over 255 gives the level back.
TEST(StampShading, QuantisingALevelGivesItBack) {
    for (int k = 0; k < 256; ++k) EXPECT_EQ(shade::quantise(float(k) / 255.0f), k);
}

}  // namespace
}  // namespace tessera
