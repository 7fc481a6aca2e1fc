// Environment backgrounds: cube-map face selection and orientation (OpenGL's table), the
// procedural sky, and the pixel rays FrameShading uses for them.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <vector>

#include "raster/core/error.h"
#include "raster/shade/background_radiance.h"
#include "raster/shade/frame_shading.h"

using namespace tessera;

namespace {

std::shared_ptr<const texture::Texture> solid(glm::vec3 c) {
    return std::make_shared<const texture::Texture>(1, 1, std::vector<glm::vec4>{glm::vec4(c, 1.0f)});
}

// A cube map whose every face is the 2 x 2 image file (top row first): red green / blue white.
scene::Background quadrant_cube_map() {
    io::FloatImage image;
    image.width = image.height = 2;
    image.channels = 3;
    image.pixels = {1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 1, 1};
    scene::Background b;
    b.kind = scene::Background::Kind::cube_map;
    for (auto& face : b.cube.faces)
        face = std::make_shared<const texture::Texture>(texture::Texture::from_image(image, texture::TexelEncoding::linear));
    return b;
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
    const scene::Background b = quadrant_cube_map();
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

namespace {

using simd::vfloat;

uint32_t bits_of(float f) { return std::bit_cast<uint32_t>(f); }

// Directions that probe every branch of the sky and of the normalisation: a latitude-longitude
// grid, the poles, both sides of the horizon and of its bands, around the sun disc's edge,
// and lengths that are zero, tiny, huge, infinite or NaN.
std::vector<glm::vec3> probe_directions(glm::vec3 sun) {
    std::vector<glm::vec3> d;
    for (int i = 0; i <= 96; ++i)
        for (int j = 0; j < 64; ++j) {
            const double elevation = (double(i) / 96.0 - 0.5) * 3.14159265358979, azimuth = double(j) * 0.0981747704;
            d.push_back({float(std::cos(elevation) * std::cos(azimuth)), float(std::sin(elevation)),
                         float(std::cos(elevation) * std::sin(azimuth))});
        }
    const float inf = std::numeric_limits<float>::infinity(), nan = std::numeric_limits<float>::quiet_NaN();
    for (float y : {0.0f, -0.0f, 1e-30f, -1e-30f, 1e-45f, -1e-45f, 1e-7f, -1e-7f, 0.0999f, 0.1f, 0.1001f, -0.2499f,
                    -0.25f, -0.2501f, 0.999f, -0.999f})
        d.push_back({std::sqrt(std::max(0.0f, 1.0f - y * y)), y, 0.0f});
    for (glm::vec3 v : {glm::vec3(0, 1, 0), glm::vec3(0, -1, 0), glm::vec3(0, 1e30f, 0), glm::vec3(0, -1e-30f, 0),
                        glm::vec3(0), glm::vec3(-0.0f), glm::vec3(inf, 0, 0), glm::vec3(0, -inf, 1), glm::vec3(nan, 0, 0),
                        glm::vec3(0, 0, nan), glm::vec3(3e38f, 3e38f, 0), glm::vec3(1e-40f, 0, 0)})
        d.push_back(v);
    // Around the sun: the disc's edge (cosine 0.9995, about 1.81 degrees) and the glow.
    const glm::vec3 s = glm::length(sun) > 0.0f ? glm::normalize(sun) : glm::vec3(0, 1, 0);
    const glm::vec3 side = glm::normalize(glm::cross(s, glm::vec3(0.3f, 0.1f, 0.9f)));
    for (int k = 0; k <= 400; ++k) {
        const float angle = float(k) * 0.0002f;  // 0 .. 4.6 degrees
        d.push_back(s * std::cos(angle) + side * std::sin(angle));
    }
    d.push_back(s);
    d.push_back(-s);
    d.push_back(s * 1e20f);
    return d;
}

// The lane form of background_radiance against the one-direction form, bit for bit, over
// `directions` packed kLanes at a time (in both orders, so each lands in different lanes).
void expect_lanes_equal_one_by_one(const scene::Background& b, std::vector<glm::vec3> directions) {
    constexpr int N = simd::kLanes;
    for (int pass = 0; pass < 2; ++pass) {
        if (pass == 1) std::reverse(directions.begin(), directions.end());
        for (size_t start = 0; start < directions.size(); start += N) {
            alignas(64) float x[N], y[N], z[N];
            for (int i = 0; i < N; ++i) {
                const glm::vec3 v = directions[std::min(start + size_t(i), directions.size() - 1)];
                x[i] = v.x;
                y[i] = v.y;
                z[i] = v.z;
            }
            const simd::V3<vfloat> c = shade::background_radiance_lanes(b, {vfloat::load(x), vfloat::load(y), vfloat::load(z)});
            alignas(64) float r[N], g[N], bl[N];
            c.x.store(r);
            c.y.store(g);
            c.z.store(bl);
            for (int i = 0; i < N; ++i) {
                const glm::vec3 d(x[i], y[i], z[i]);
                const glm::vec3 one = shade::background_radiance(b, d);
                ASSERT_TRUE(std::isfinite(one.r) && std::isfinite(one.g) && std::isfinite(one.b))
                    << d.x << " " << d.y << " " << d.z;
                ASSERT_EQ(bits_of(r[i]), bits_of(one.r)) << d.x << " " << d.y << " " << d.z;
                ASSERT_EQ(bits_of(g[i]), bits_of(one.g)) << d.x << " " << d.y << " " << d.z;
                ASSERT_EQ(bits_of(bl[i]), bits_of(one.b)) << d.x << " " << d.y << " " << d.z;
            }
        }
    }
}

}  // namespace

TEST(ShadingBackground, SkyInLanesEqualsTheOneDirectionFormBitForBit) {
    scene::Background b;
    b.kind = scene::Background::Kind::sky;
    expect_lanes_equal_one_by_one(b, probe_directions(b.sky.sun_direction));
    b.sky.sun_direction = {-0.2f, -0.9f, 0.1f};  // below the horizon
    expect_lanes_equal_one_by_one(b, probe_directions(b.sky.sun_direction));
    b.sky.sun_direction = glm::vec3(0.0f);  // no sun
    expect_lanes_equal_one_by_one(b, probe_directions(glm::vec3(0.0f)));
    b.kind = scene::Background::Kind::colour;
    b.colour = {0.1f, 0.2f, 0.3f};
    expect_lanes_equal_one_by_one(b, probe_directions(glm::vec3(1.0f)));
}

TEST(ShadingBackground, CubeMapInLanesEqualsTheOneDirectionForm) {
    const scene::Background b = quadrant_cube_map();
    std::vector<glm::vec3> directions = probe_directions(glm::vec3(1.0f));
    directions.resize(600);  // texture lookups are the slow part; the grid's first rows suffice
    expect_lanes_equal_one_by_one(b, directions);
}

// The sky's glow is cos^64 by six squarings in double precision (one rounding): within a few
// units in the last place of the sky with std::pow's power, which is within one unit of the
// exact one.
TEST(ShadingBackground, SkyGlowIsThePowerOfTheCosine) {
    scene::Background b;
    b.kind = scene::Background::Kind::sky;
    b.sky.zenith = b.sky.horizon = b.sky.ground = glm::vec3(0.0f);
    b.sky.sun = glm::vec3(50.0f);  // radiance = 50 * (0.02 * cos^64) = cos^64 where it glows
    const glm::vec3 s = b.sky.sun_direction / glm::length(b.sky.sun_direction);  // as the sky divides
    int glowing = 0;
    for (const glm::vec3& d : probe_directions(b.sky.sun_direction)) {
        const float len = glm::length(d);
        if (!(len > 0.0f) || !std::isfinite(len)) continue;
        const float cosine = glm::dot(d / len, s);
        if (!(cosine > 0.0f) || cosine > 0.9995f) continue;
        const double exact = std::pow(double(cosine), 64.0);
        const float got = shade::background_radiance(b, d).r;
        ASSERT_NEAR(got, exact, 4e-7 * exact + 1e-37) << cosine;
        glowing += exact > 1e-3;
    }
    EXPECT_GT(glowing, 100);
}

TEST(ShadingBackground, BackgroundPassInLanesEqualsThePixelByPixelReference) {
    scene::Scene scene;
    scene.background.kind = scene::Background::Kind::sky;
    const scene::BakedScene baked = scene::bake(scene);
    // Views across the horizon, straight up and down (the up vector off the view axis) and
    // into the sun; 67 x 45 leaves partial lane groups at each row's end.
    const glm::vec3 looks[] = {{0, 0, -1}, {0, 1, 0.001f}, {0, -1, 0.001f}, glm::normalize(scene.background.sky.sun_direction)};
    for (const glm::vec3 look : looks) {
        scene.camera.eye = {0, 0, 0};
        scene.camera.lookat = look;
        scene.camera.fovy_deg = 100.0f;
        const int w = 67, h = 45;
        const shade::FrameShading shading(baked, scene, shade::RenderState{scene.camera, w, h, {}});
        VisibilityBuffer visibility;
        visibility.reset(w, h);
        std::vector<uint8_t> coverage(size_t(w) * size_t(h), 1);
        for (size_t i = 0; i < coverage.size(); i += 7) visibility.triangle[i] = 3;  // surfaces: left alone
        for (size_t i = 0; i < coverage.size(); i += 11) coverage[i] = 0;            // not this tile's
        std::vector<glm::vec4> lanes(coverage.size(), glm::vec4(-1.0f)), one(coverage.size(), glm::vec4(-1.0f));
        for (const TileRect rect : {TileRect{0, 0, w, h}, TileRect{5, 3, 40, 20}}) {
            Tile a = frame_tile(visibility, lanes.data(), rect), b = frame_tile(visibility, one.data(), rect);
            a.coverage = b.coverage = coverage.data() + size_t(rect.y0) * size_t(w) + size_t(rect.x0);
            shade::shade_background(shading, a);
            shade::shade_background_reference(shading, b);
        }
        ASSERT_EQ(0, std::memcmp(lanes.data(), one.data(), lanes.size() * sizeof(glm::vec4))) << look.y;
        EXPECT_EQ(lanes[1], shading.background(1, 0));
        EXPECT_EQ(lanes[7], glm::vec4(-1.0f));   // a surface
        EXPECT_EQ(lanes[11], glm::vec4(-1.0f));  // another tile's
    }
}
