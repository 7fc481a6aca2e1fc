// The SIMD shading pass (stamp_shading.h) against the scalar reference (reference_shading.h):
// bit-identical for id, depth and normal; for phong within one 8-bit level per channel, on a
// tiny fraction of the channels (the x^48 of repeated squaring vs powf, bound in
// stamp_shading.h), on a meshed sphere with normals and uv and on one with face normals.
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

std::vector<uint8_t> shade(const Mesh& mesh, shade::ShadeMode mode, bool simd, bool tile_color) {
    const Camera camera = sphere_camera();
    std::vector<uint8_t> rgb8(size_t(kWidth) * kHeight * 3, 7);
    const pipeline::TilePass pass = simd ? shade::make_stamp_shading_pass(mode, camera, rgb8)
                               : shade::make_reference_shading_pass(mode, camera, rgb8);
    pipeline::RasterOptions options;
    options.tile_size = 64;
    options.tile_color = tile_color;
    VisibilityBuffer vis;
    pipeline::Rasterizer().render(mesh, camera.view_projection(), pipeline::Viewport(kWidth, kHeight), options, vis, {&pass, 1});
    return rgb8;
}

struct Difference {
    size_t channels = 0, lit = 0;
    int max = 0;
};

Difference compare(const Mesh& mesh, shade::ShadeMode mode) {
    const std::vector<uint8_t> reference = shade(mesh, mode, false, true);
    const std::vector<uint8_t> fast = shade(mesh, mode, true, false);
    Difference d;
    for (size_t i = 0; i < reference.size(); ++i) {
        const int delta = std::abs(int(reference[i]) - int(fast[i]));
        d.channels += delta != 0;
        d.max = std::max(d.max, delta);
        d.lit += reference[i] != 0;
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
    for (const Mesh& mesh : {workloads::sphere(200, 120), face_normal_sphere()})
        for (shade::ShadeMode mode : {shade::ShadeMode::id, shade::ShadeMode::depth, shade::ShadeMode::normal}) {
            const Difference d = compare(mesh, mode);
            EXPECT_EQ(d.channels, 0u) << int(mode);
            EXPECT_GT(d.lit, size_t(kWidth) * kHeight / 4) << int(mode);  // the sphere is on screen
        }
}

TEST(StampShading, PhongWithinOneLevel) {
    for (const Mesh& mesh : {workloads::sphere(200, 120), face_normal_sphere()}) {
        const Difference d = compare(mesh, shade::ShadeMode::phong);
        EXPECT_LE(d.max, 1);
        EXPECT_LE(d.channels, d.lit / 1000);  // rounding-boundary cases only
        EXPECT_GT(d.lit, size_t(kWidth) * kHeight / 4);
    }
}

}  // namespace
}  // namespace tessera
