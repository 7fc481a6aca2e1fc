// The compute passes on a frame's depth and colour: a marched sphere lands at the analytic
// window depth, it and a pre-filled "rasterized" plane occlude each other per pixel by true
// distance, tiles give the same bytes as one big rectangle, the background fills exactly
// the empty pixels and the fog uses the distance the depth buffer implies.
#include "raster/march/surface_pass.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <vector>

#include "raster/march/background_pass.h"
#include "raster/march/fog_pass.h"
#include "march_fixtures.h"

using namespace tessera;
using namespace tessera::march;
using namespace tessera::test;

namespace {

constexpr int W = 40, H = 32;

struct Frame {
    std::vector<float> depth = std::vector<float>(W * H, 1.0f);
    std::vector<glm::vec4> colour = std::vector<glm::vec4>(W * H, glm::vec4(0.0f));
    Tile tile(int x0, int y0, int x1, int y1) {
        return {{x0, y0, x1, y1}, nullptr, depth.data() + y0 * W + x0, W, colour.data() + y0 * W + x0, W};
    }
    Tile all() { return tile(0, 0, W, H); }
};

scene::Background sky_background() {
    scene::Background b;
    b.kind = scene::Background::Kind::sky;
    return b;
}

}  // namespace

TEST(MarchPass, MarchedSphereLandsAtItsAnalyticDepth) {
    const Camera camera = march_camera(W, H);
    const RayGenerator rays(camera, W, H);
    const scene::Background env = sky_background();
    Frame frame;
    sphere_pass(rays, env).run(frame.all());
    int covered = 0;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            const glm::vec3 d = rays.direction(x, y);
            const double t = unit_sphere_distance(camera.eye, d);
            const float depth = frame.depth[y * W + x];
            if (std::isinf(t) || t > 3.6) {  // missed, or a grazing hit the march may tunnel
                if (std::isinf(t)) {
                    EXPECT_EQ(depth, 1.0f) << x << "," << y;
                }
                continue;
            }
            EXPECT_NEAR(depth, rays.window_depth(camera.eye + d * float(t)), 2e-5f) << x << "," << y;
            EXPECT_NEAR(rays.distance_from_depth(x, y, depth), t, 1e-3) << x << "," << y;
            EXPECT_EQ(frame.colour[y * W + x].a, 1.0f);
            ++covered;
        }
    EXPECT_GT(covered, 100);
}

TEST(MarchPass, MarchedSurfaceAndRasterizedPlaneOccludeEachOther) {
    // A plane z = 0.6 already in the depth buffer on the left half ("rasterized", green):
    // the sphere's cap (z up to 1) pokes through it, its flanks (z < 0.6) hide behind it.
    const Camera camera = march_camera(W, H);
    const RayGenerator rays(camera, W, H);
    const scene::Background env = sky_background();
    Frame frame;
    const glm::vec4 green(0.0f, 1.0f, 0.0f, 1.0f);
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W / 2; ++x) {
            const glm::vec3 d = rays.direction(x, y);
            const float t = (0.6f - camera.eye.z) / d.z;
            frame.depth[y * W + x] = rays.window_depth(camera.eye + d * t);
            frame.colour[y * W + x] = green;
        }
    sphere_pass(rays, env).run(frame.all());
    int sphere_in_front = 0, plane_in_front = 0;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W / 2; ++x) {
            const glm::vec3 d = rays.direction(x, y);
            const double ts = unit_sphere_distance(camera.eye, d);
            const double tp = (0.6 - camera.eye.z) / d.z;
            if (std::fabs(ts - tp) < 0.02 || (!std::isinf(ts) && ts > 3.6)) continue;  // near ties, grazing
            const bool sphere_wins = ts < tp;
            EXPECT_EQ(frame.colour[y * W + x] != green, sphere_wins) << x << "," << y;
            (sphere_wins ? sphere_in_front : plane_in_front)++;
        }
    EXPECT_GT(sphere_in_front, 20);
    EXPECT_GT(plane_in_front, 20);
}

TEST(MarchPass, TilesGiveTheSameBytesAsOneRectangle) {
    const RayGenerator rays(march_camera(W, H), W, H);
    const scene::Background env = sky_background();
    Fog fog;
    fog.density = {0.05f, 0.07f, 0.09f};
    fog.colour = {0.6f, 0.6f, 0.7f};
    fog.falloff = 0.8f;
    const FogPass fog_pass(rays, fog);
    const BackgroundPass background(rays, env);
    const auto pass = sphere_pass(rays, env);
    Frame whole, tiled;
    pass.run(whole.all());
    background.run(whole.all());
    fog_pass.run(whole.all());
    // Odd tile sizes, visited in reverse order.
    for (int ty = H; ty > 0; ty -= 13)
        for (int tx = W; tx > 0; tx -= 11) {
            const Tile t = tiled.tile(std::max(0, tx - 11), std::max(0, ty - 13), tx, ty);
            pass.run(t);
            background.run(t);
            fog_pass.run(t);
        }
    EXPECT_EQ(std::memcmp(whole.depth.data(), tiled.depth.data(), sizeof(float) * W * H), 0);
    EXPECT_EQ(std::memcmp(whole.colour.data(), tiled.colour.data(), sizeof(glm::vec4) * W * H), 0);
}

TEST(MarchPass, BackgroundFillsEmptyPixelsAndFogUsesTheDepthDistance) {
    const Camera camera = march_camera(W, H);
    const RayGenerator rays(camera, W, H);
    const scene::Background env = sky_background();
    Frame frame;
    sphere_pass(rays, env).run(frame.all());
    const Frame shaded = frame;
    BackgroundPass(rays, env).run(frame.all());
    Fog fog;
    fog.density = glm::vec3(0.2f);
    fog.colour = {0.5f, 0.5f, 0.5f};
    fog.falloff = 0.5f;
    FogPass(rays, fog).run(frame.all());
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            const glm::vec3 d = rays.direction(x, y);
            const float depth = frame.depth[y * W + x];
            const glm::vec3 before = depth < 1.0f ? glm::vec3(shaded.colour[y * W + x]) : shade::background_radiance(env, d);
            const float distance = depth < 1.0f ? float(unit_sphere_distance(camera.eye, d)) : INFINITY;
            if (depth < 1.0f && std::isinf(distance)) continue;
            const glm::vec3 expected = fog.apply(before, camera.eye, d, distance);
            const glm::vec3 got(frame.colour[y * W + x]);
            EXPECT_NEAR(got.x, expected.x, 2e-4f) << x << "," << y;
            EXPECT_NEAR(got.z, expected.z, 2e-4f) << x << "," << y;
        }
}

// In fog the far plane is where sight ends: a surface melts into the fog colour over the last
// quarter of the far distance instead of ending at a hard edge; nearer ones keep the closed form.
TEST(MarchPass, FogHidesTheFarPlane) {
    const Camera camera = march_camera(W, H);
    const RayGenerator rays(camera, W, H);
    Fog fog;
    fog.density = glm::vec3(1e-4f);  // thin: transmittance ~1 everywhere in range
    fog.colour = {0.5f, 0.6f, 0.7f};
    const int y = H / 2;
    const glm::vec3 d = rays.direction(W / 2, y);
    const float far = rays.far_distance(d);
    const glm::vec4 red(1.0f, 0.0f, 0.0f, 1.0f);
    float previous_red = 2.0f;
    for (float fraction : {0.5f, 0.74f, 0.8f, 0.9f, 0.95f, 0.99f, 0.9999f}) {
        Frame frame;
        frame.colour[size_t(y) * W + W / 2] = red;
        frame.depth[size_t(y) * W + W / 2] = rays.window_depth(camera.eye + d * (fraction * far));
        FogPass(rays, fog).run(frame.all());
        const glm::vec4 got = frame.colour[size_t(y) * W + W / 2];
        const glm::vec3 closed_form = fog.apply(glm::vec3(red), camera.eye, d, fraction * far);
        if (fraction < 0.75f) EXPECT_NEAR(got.r, closed_form.r, 1e-5f) << fraction;
        if (fraction > 0.999f) EXPECT_NEAR(got.g, fog.colour.g, 1e-2f) << fraction;
        EXPECT_LE(got.r, previous_red) << "fades monotonically, at " << fraction;
        previous_red = got.r;
    }
    // The sky beyond keeps the closed form (height fog seen upwards lets it through).
    Frame sky;
    sky.colour[0] = red;
    FogPass(rays, fog).run(sky.all());
    EXPECT_NEAR(sky.colour[0].r, fog.apply(glm::vec3(red), camera.eye, rays.direction(0, 0), INFINITY).r, 1e-6f);
}

TEST(MarchPass, ASurfaceCutByTheNearPlaneShowsAtTheNearPlane) {
    Camera camera = march_camera(W, H);
    camera.eye = {0.0f, 0.0f, 1.2f};  // the near plane (0.5 ahead) lies inside the sphere
    const RayGenerator rays(camera, W, H);
    const scene::Background env = sky_background();
    Frame frame;
    sphere_pass(rays, env).run(frame.all());
    const size_t centre = size_t(H / 2) * W + W / 2;
    EXPECT_EQ(frame.depth[centre], 0.0f);
    EXPECT_EQ(frame.colour[centre].a, 1.0f);
}

TEST(MarchPass, BadPassParametersAreRefused) {
    const RayGenerator rays(march_camera(W, H), W, H);
    const scene::Background env = sky_background();
    MarchSettings zero_steps;
    zero_steps.steps = 0;
    using Pass = SurfacePass<SlabSurface<SphereField>>;
    EXPECT_THROW(Pass(SlabSurface<SphereField>{kUnitSphere, Slab{}}, rays, zero_steps, SurfaceLook{}, env),
                 std::invalid_argument);
    SurfaceLook look;
    look.normals.method = NormalMethod::central_differences;
    look.normals.h = std::nanf("");
    EXPECT_THROW(Pass(SlabSurface<SphereField>{kUnitSphere, Slab{}}, rays, MarchSettings{}, look, env),
                 std::invalid_argument);
    EXPECT_THROW(Pass(SlabSurface<SphereField>{kUnitSphere, Slab{1.0f, std::nanf("")}}, rays, MarchSettings{},
                      SurfaceLook{}, env),
                 std::invalid_argument);
    Fog fog;
    fog.density = glm::vec3(-1.0f);
    EXPECT_THROW(FogPass(rays, fog), std::invalid_argument);
}
