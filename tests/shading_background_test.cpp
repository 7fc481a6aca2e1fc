// Environment backgrounds: cube-map face selection and orientation (OpenGL's table), the
// procedural sky, and the pixel rays FrameShading uses for them.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "raster/core/error.h"
#include "raster/shade/background_radiance.h"
#include "raster/shade/frame_shading.h"

using namespace tessera;

namespace {

std::shared_ptr<const texture::Texture> solid(glm::vec3 c) {
    return std::make_shared<const texture::Texture>(1, 1, std::vector<glm::vec4>{glm::vec4(c, 1.0f)});
}

}  // namespace

TEST(ShadingBackground, CubeMapSelectsTheMajorAxisFace) {
    scene::Background b;
    b.kind = scene::Background::Kind::cube_map;
    const glm::vec3 colours[6] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 0}, {0, 1, 1}, {1, 0, 1}};
    for (int i = 0; i < 6; ++i) b.cube.faces[size_t(i)] = solid(colours[i]);
    const glm::vec3 directions[6] = {{2, 0.5f, -1}, {-2, 1, 1}, {0.3f, 5, 0}, {0, -1, 0.2f}, {0.1f, 0.1f, 3}, {0, 0.4f, -1}};
    for (int i = 0; i < 6; ++i) EXPECT_EQ(shade::background_radiance(b, directions[i]), colours[i]) << "face " << i;
}

TEST(ShadingBackground, CubeMapFaceOrientationFollowsOpenGL) {
    // A 2 x 2 +z face given as an image file would be (top row first): red green / blue white.
    io::FloatImage image;
    image.width = image.height = 2;
    image.channels = 3;
    image.pixels = {1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 1, 1};
    scene::Background b;
    b.kind = scene::Background::Kind::cube_map;
    for (auto& face : b.cube.faces) face = std::make_shared<const texture::Texture>(texture::Texture::from_image(image, texture::TexelEncoding::linear));
    // +z: s = (x/|z| + 1)/2, t = (-y/|z| + 1)/2, t = 0 at the image's top row, so direction
    // (-x, +y) reads (s, t) = (0.25, 0.25), the image's top-left texel. (OpenGL cube maps are
    // left-handed: skybox images are authored for this table.)
    EXPECT_EQ(shade::background_radiance(b, {-0.5f, 0.5f, 1.0f}), glm::vec3(1, 0, 0));
    EXPECT_EQ(shade::background_radiance(b, {0.5f, 0.5f, 1.0f}), glm::vec3(0, 1, 0));
    EXPECT_EQ(shade::background_radiance(b, {-0.5f, -0.5f, 1.0f}), glm::vec3(0, 0, 1));
    EXPECT_EQ(shade::background_radiance(b, {0.5f, -0.5f, 1.0f}), glm::vec3(1, 1, 1));
}

TEST(ShadingBackground, MissingCubeFacesAreClearErrors) {
    EXPECT_THROW(scene::load_cube_map("/nonexistent/sky_{face}.png"), Error);
    EXPECT_THROW(scene::load_cube_map("/nonexistent/sky.png"), std::invalid_argument);
}

TEST(ShadingBackground, SkyIsBrighterUpThanDownAndShowsTheSun) {
    scene::Background b;
    b.kind = scene::Background::Kind::sky;
    const glm::vec3 up = shade::background_radiance(b, {0, 1, 0}), down = shade::background_radiance(b, {0, -1, 0});
    EXPECT_GT(up.b, down.b);
    EXPECT_EQ(shade::background_radiance(b, b.sky.sun_direction), b.sky.sun);
    EXPECT_TRUE(std::isfinite(shade::background_radiance(b, {0, 0, 0}).r));  // zero direction: no NaN
}

// A kink in the sky's gradient at the horizon is a bright line there, and a curved mirror shows
// it as a crease: the colour must change smoothly across the horizon (slope 0 on both sides,
// no jump in slope anywhere) and keep its sqrt(elevation) law above the horizon band.
TEST(ShadingBackground, SkyHasNoKinkAtTheHorizon) {
    scene::Background b;
    b.kind = scene::Background::Kind::sky;
    b.sky.sun = glm::vec3(0.0f);  // no glow: the gradient alone
    const auto at = [&](double elevation) {
        return glm::dvec3(shade::background_radiance(b, {float(std::cos(elevation)), float(std::sin(elevation)), 0.0f}));
    };
    const double h = 1e-3;
    const double above = glm::length(at(h) - at(0.0)) / h, below = glm::length(at(0.0) - at(-h)) / h;
    EXPECT_LT(above, 0.2) << "slope just above the horizon, per radian";
    EXPECT_LT(below, 0.2) << "slope just below the horizon, per radian";
    // The slope changes by little from step to step across [-30, 30] degrees.
    double worst = 0.0;
    for (double e = -0.5; e < 0.5; e += h)
        worst = std::max(worst, glm::length(at(e + h) - 2.0 * at(e) + at(e - h)) / h);
    EXPECT_LT(worst, 1.0) << "largest jump in slope between neighbouring 1 mrad steps";
    const float up = 0.5f;
    const glm::vec3 expected = glm::mix(b.sky.horizon, b.sky.zenith, std::sqrt(up));
    const glm::vec3 got = shade::background_radiance(b, {std::sqrt(1.0f - up * up), up, 0.0f});
    EXPECT_NEAR(got.r, expected.r, 1e-5f);
    EXPECT_NEAR(got.b, expected.b, 1e-5f);
}

TEST(ShadingBackground, PixelRaysLookThroughTheCamera) {
    // A scene with no objects: the centre pixel sees along the view direction, the top row up.
    scene::Scene scene;
    scene.camera.eye = {0, 0, 0};
    scene.camera.lookat = {0, 0, -1};
    scene.camera.aspect = 1.0f;
    scene.background.kind = scene::Background::Kind::cube_map;
    const glm::vec3 colours[6] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 0}, {0, 1, 1}, {1, 0, 1}};
    for (int i = 0; i < 6; ++i) scene.background.cube.faces[size_t(i)] = solid(colours[i]);
    scene.camera.fovy_deg = 120.0f;
    const scene::BakedScene baked = scene::bake(scene);
    const shade::FrameShading shading(baked, scene, shade::RenderState{scene.camera, 33, 33, {}});
    EXPECT_EQ(glm::vec3(shading.background(16, 16)), colours[5]);  // -z
    EXPECT_EQ(glm::vec3(shading.background(16, 0)), colours[2]);   // +y (top row, fov 120)
    EXPECT_EQ(glm::vec3(shading.background(32, 16)), colours[0]);  // +x
}
