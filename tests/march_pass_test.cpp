// The compute passes on a frame's depth and colour: a marched sphere lands at the analytic
// window depth, it and a pre-filled "rasterized" plane occlude each other per pixel by true
// distance, tiles give the same bytes as one big rectangle, the background fills exactly
// the empty pixels and the fog uses the distance the depth buffer implies.
#include "raster/march/surface_pass.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <iterator>
#include <limits>
#include <vector>

#include "procedural/field.h"
#include "raster/march/background_pass.h"
#include "raster/march/fog_pass.h"
#include "raster/march/metaball_orbits.h"
#include "raster/march/procedural_surfaces.h"
#include "raster/pipeline/sample_pattern.h"
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
        if (fraction < 0.75f) {
            EXPECT_NEAR(got.r, closed_form.r, 1e-5f) << fraction;
        }
        if (fraction > 0.999f) {
            EXPECT_NEAR(got.g, fog.colour.g, 1e-2f) << fraction;
        }
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

namespace {

// A depth buffer with every kind of value the fog pass meets: the sphere's depths, the cleared
// 1.0, depths from the near plane to beyond the far fade, and 0.
Frame fog_probe_frame(const RayGenerator& rays, const Camera& camera, const scene::Background& env) {
    Frame frame;
    sphere_pass(rays, env).run(frame.all());
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            const size_t i = size_t(y) * W + size_t(x);
            frame.colour[i] = glm::vec4(float(x) / W, float(y) / H, 0.5f, 0.75f);
            if (frame.depth[i] < 1.0f || (x + y) % 3 == 0) continue;
            const glm::vec3 d = rays.direction(x, y);
            const float fraction = float((x * 7 + y * 3) % 41) / 40.0f * 1.05f;  // up to past the far plane
            frame.depth[i] = (x + y) % 7 == 0 ? 0.0f : rays.window_depth(camera.eye + d * (fraction * rays.far_distance(d)));
        }
    return frame;
}

}  // namespace

TEST(MarchPass, RayLanesEqualTheOnePixelForms) {
    for (const glm::vec3 lookat : {glm::vec3(0.0f), glm::vec3(0.4f, 50.0f, 3.9f), glm::vec3(0.4f, -50.0f, 3.9f)}) {
        Camera camera = march_camera(W, H);
        camera.lookat = lookat;
        const RayGenerator rays(camera, W, H);
        constexpr int N = simd::kLanes;
        const float depths[] = {0.0f, 0.3f, 0.9f, 0.999999f, 1.0f, 2.0f, std::numeric_limits<float>::quiet_NaN()};
        for (int y = 0; y < H; ++y)
            for (int x0 = 0; x0 < W; x0 += N) {
                alignas(64) float depth[N], dx[N], dy[N], dz[N], distance[N];
                for (int i = 0; i < N; ++i) depth[i] = depths[size_t(x0 + i + y) % std::size(depths)];
                const simd::V3<simd::vfloat> d = rays.directions(x0, y);
                d.x.store(dx);
                d.y.store(dy);
                d.z.store(dz);
                rays.distances_from_depth(x0, y, simd::vfloat::load(depth)).store(distance);
                for (int i = 0; i < N; ++i) {
                    const glm::vec3 one = rays.direction(x0 + i, y);
                    ASSERT_EQ(std::bit_cast<uint32_t>(dx[i]), std::bit_cast<uint32_t>(one.x)) << x0 + i << "," << y;
                    ASSERT_EQ(std::bit_cast<uint32_t>(dy[i]), std::bit_cast<uint32_t>(one.y)) << x0 + i << "," << y;
                    ASSERT_EQ(std::bit_cast<uint32_t>(dz[i]), std::bit_cast<uint32_t>(one.z)) << x0 + i << "," << y;
                    ASSERT_EQ(std::bit_cast<uint32_t>(distance[i]),
                              std::bit_cast<uint32_t>(rays.distance_from_depth(x0 + i, y, depth[i])))
                        << x0 + i << "," << y << " depth " << depth[i];
                }
            }
    }
}

TEST(MarchPass, FogTransmittanceInLanesEqualsTheOneRayForm) {
    constexpr int N = simd::kLanes;
    const float inf = std::numeric_limits<float>::infinity(), nan = std::numeric_limits<float>::quiet_NaN();
    const float dys[] = {0.0f, -0.0f, 1e-9f, -1e-9f, 1e-6f, 2e-5f, -2e-5f, 0.3f, -0.3f, 1.0f, -1.0f, 0.999f};
    const float distances[] = {0.0f, -1.0f, 1e-30f, 0.01f, 1.0f, 7.5f, 100.0f, 1e6f, 3e38f, inf, nan};
    for (const float falloff : {0.0f, 0.05f, 0.8f, 4.0f})
        for (const float base : {-3.0f, 0.0f, 2.5f}) {
            Fog fog;
            fog.density = {0.2f, 0.0f, 3.0f};  // a clear channel too
            fog.falloff = falloff;
            fog.base_height = base;
            const glm::vec3 eye(0.4f, 1.3f, 4.0f);
            const size_t cases = std::size(dys) * std::size(distances);
            for (size_t start = 0; start < cases; start += N) {
                alignas(64) float dy[N], distance[N], t[3][N];
                for (int i = 0; i < N; ++i) {
                    const size_t k = std::min(start + size_t(i), cases - 1);
                    dy[i] = dys[k % std::size(dys)];
                    distance[i] = distances[k / std::size(dys)];
                }
                const simd::V3<simd::vfloat> lanes = fog.transmittance(eye, simd::vfloat::load(dy), simd::vfloat::load(distance));
                lanes.x.store(t[0]);
                lanes.y.store(t[1]);
                lanes.z.store(t[2]);
                for (int i = 0; i < N; ++i) {
                    const glm::vec3 one = fog.transmittance(eye, {0.0f, dy[i], 0.0f}, distance[i]);
                    for (int c = 0; c < 3; ++c) {
                        // NaN only where falloff * dy * D overflows (D near FLT_MAX), in both.
                        if (!(distance[i] > 1e30f)) {
                            ASSERT_FALSE(std::isnan(one[c])) << "dy " << dy[i] << " D " << distance[i];
                        }
                        if (std::isnan(one[c]) && std::isnan(t[c][i])) continue;
                        ASSERT_EQ(std::bit_cast<uint32_t>(t[c][i]), std::bit_cast<uint32_t>(one[c]))
                            << "falloff " << falloff << " dy " << dy[i] << " distance " << distance[i] << " channel " << c;
                    }
                }
            }
        }
}

// The per-pixel passes in lanes against their one-pixel references: background and fog over
// sphere, empty, near, far-faded and beyond-far pixels, for a camera looking across the
// horizon, up and down, with constant and height fog; pixels another tile owns are left alone.
// With coverage (some pixels held by no surface of this tile) and without (every pixel is).
TEST(MarchPass, FogAndBackgroundInLanesEqualThePixelByPixelReference) {
    const scene::Background env = sky_background();
    for (const bool with_coverage : {true, false}) {
        for (const glm::vec3 lookat : {glm::vec3(0.0f), glm::vec3(0.4f, 50.0f, 3.9f), glm::vec3(0.4f, -50.0f, 3.9f)})
            for (const float falloff : {0.0f, 0.8f}) {
                Camera camera = march_camera(W, H);
                camera.lookat = lookat;
                const RayGenerator rays(camera, W, H);
                Fog fog;
                fog.density = {0.05f, 0.0f, 0.3f};
                fog.colour = {0.6f, 0.6f, 0.7f};
                fog.falloff = falloff;
                const FogPass fog_pass(rays, fog);
                const BackgroundPass background(rays, env);
                const Frame start = fog_probe_frame(rays, camera, env);
                std::vector<uint8_t> coverage(size_t(W) * H, 1);
                for (size_t i = 0; i < coverage.size(); i += 5) coverage[i] = 0;
                Frame lanes = start, one = start;
                for (const TileRect r : {TileRect{0, 0, W, H}, TileRect{3, 2, 29, 17}}) {
                    Tile a = lanes.tile(r.x0, r.y0, r.x1, r.y1), b = one.tile(r.x0, r.y0, r.x1, r.y1);
                    background.run(a);
                    background.run_reference(b);
                    if (with_coverage) a.coverage = b.coverage = coverage.data() + size_t(r.y0) * W + size_t(r.x0);
                    fog_pass.run(a);
                    fog_pass.run_reference(b);
                }
                ASSERT_EQ(std::memcmp(lanes.colour.data(), one.colour.data(), sizeof(glm::vec4) * W * H), 0)
                    << "falloff " << falloff << " looking at y " << lookat.y << " coverage " << with_coverage;
                if (with_coverage) {
                    EXPECT_EQ(lanes.colour[5], start.colour[5]);  // not this tile's: no fog
                }
                EXPECT_NE(lanes.colour[1], start.colour[1]);
            }
    }
}

// The surface pass in lanes against its ray-by-ray reference, bit for bit: every kind of field
// (a sphere, whose gradient has no packet form; metaballs, with the packet bound, a mirror
// term and each kernel; the ridged terrain and the noise volume through their batch
// gradients; the gradient noise through its packet gradient; central differences), over a
// frame where a "rasterized" plane covers part of the view, in two overlapping rectangles
// whose packets end part-way, some pixels outside the coverage.
TEST(MarchPass, SurfacePassInLanesEqualsTheRayByRayReference) {
    const Camera camera = march_camera(W, H);
    const RayGenerator rays(camera, W, H);
    const scene::Background env = sky_background();
    Frame start;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W / 2; ++x) {
            const glm::vec3 d = rays.direction(x, y);
            start.depth[y * W + x] = rays.window_depth(camera.eye + d * ((0.3f - camera.eye.z) / d.z));
            start.colour[y * W + x] = glm::vec4(0.0f, 1.0f, 0.0f, 1.0f);
        }
    std::vector<uint8_t> coverage(size_t(W) * H, 1);
    for (size_t i = 0; i < coverage.size(); i += 7) coverage[i] = 0;
    const auto check = [&](const auto& pass, const char* what) {
        Frame lanes = start, one = start;
        for (const TileRect r : {TileRect{0, 0, W, H}, TileRect{5, 3, 38, 29}}) {
            Tile a = lanes.tile(r.x0, r.y0, r.x1, r.y1), b = one.tile(r.x0, r.y0, r.x1, r.y1);
            if (r.x0 > 0) a.coverage = b.coverage = coverage.data() + size_t(r.y0) * W + size_t(r.x0);
            pass.run(a);
            pass.run_reference(b);
        }
        ASSERT_EQ(std::memcmp(lanes.depth.data(), one.depth.data(), sizeof(float) * W * H), 0) << what;
        ASSERT_EQ(std::memcmp(lanes.colour.data(), one.colour.data(), sizeof(glm::vec4) * W * H), 0) << what;
        int drawn = 0;
        for (int i = 0; i < W * H; ++i) drawn += lanes.depth[i] != start.depth[i];
        EXPECT_GT(drawn, 50) << what;
    };
    SurfaceLook mirror;
    mirror.material.reflectivity = 0.3f;
    SurfaceLook differences;
    differences.normals.method = NormalMethod::central_differences;
    MarchSettings geometric;
    geometric.strategy = StepStrategy::geometric;
    geometric.tolerance = 1e-4f;
    check(sphere_pass(rays, env), "sphere");
    for (MetaballKernel kernel : {MetaballKernel::wyvill, MetaballKernel::blinn, MetaballKernel::perlin}) {
        const MetaballField balls(orbiting_metaballs(5, 0.8f, 0.9f), MetaballStyle{kernel, 0.4f});
        check(SurfacePass<MetaballSurface>(MetaballSurface{balls}, rays, MarchSettings{}, mirror, env), "metaballs");
        check(SurfacePass<MetaballSurface>(MetaballSurface{balls}, rays, geometric, differences, env), "metaballs, differences");
    }
    procedural::TerrainParams relief;
    relief.relief = procedural::Relief::ridged;
    relief.fractal = {5, 2.0f, 0.5f, 3};
    relief.frequency = 0.6f;
    relief.amplitude = 1.2f;
    relief.base = -1.0f;
    const procedural::TerrainField terrain(relief);
    check(SurfacePass(terrain_surface(terrain), rays, geometric, mirror, env), "terrain");
    const procedural::NoiseVolumeField volume(procedural::VolumeParams{});
    check(SurfacePass(noise_volume_surface(volume), rays, MarchSettings{}, SurfaceLook{}, env), "noise volume");
    const GradientNoiseField noise;
    check(SurfacePass(gradient_noise_surface(noise), rays, MarchSettings{}, SurfaceLook{}, env), "gradient noise");
    check(SurfacePass(gradient_noise_surface(noise), rays, MarchSettings{}, differences, env), "gradient noise, differences");
}

namespace {

// A multisampled tile over a whole Frame: every pixel one surface of 4 samples, or the
// coverage and sample masks given.
Tile multisampled_tile(Frame& frame, const TileRect& r, const uint8_t* coverage, const uint16_t* masks) {
    Tile t = frame.tile(r.x0, r.y0, r.x1, r.y1);
    t.coverage = coverage + size_t(r.y0) * W + size_t(r.x0);
    t.sample_mask = masks + size_t(r.y0) * W + size_t(r.x0);
    t.sample_count = 4;
    t.sample_offsets = pipeline::sample_positions(4);
    return t;
}

}  // namespace

// With 4 samples, a pixel the sphere's silhouette crosses shows the mean of its samples: the
// sky's colour for those that miss (analytically, at the standard positions), the surface's for
// those that hit; pixels whose neighbourhood is all sphere or all sky keep their one-sample
// colour bit for bit.
TEST(MarchPass, MultisampledSilhouettePixelsMixSkyAndSurface) {
    const Camera camera = march_camera(W, H);
    const RayGenerator rays(camera, W, H);
    const scene::Background env = sky_background();
    const auto pass = sphere_pass(rays, env);
    const glm::vec4 sky(0.0f, 0.0f, 1.0f, 1.0f);
    Frame one, four;
    std::fill(one.colour.begin(), one.colour.end(), sky);
    four.colour = one.colour;
    const std::vector<uint8_t> coverage(size_t(W) * H, 4);
    const std::vector<uint16_t> masks(size_t(W) * H, 0xF);
    pass.run(one.all());
    pass.run(multisampled_tile(four, {0, 0, W, H}, coverage.data(), masks.data()));
    const glm::vec2* offsets = pipeline::sample_positions(4);
    int partial = 0, kept = 0;
    for (int y = 1; y < H - 1; ++y)
        for (int x = 1; x < W - 1; ++x) {
            const size_t p = size_t(y) * W + size_t(x);
            int hits = 0;
            bool clear = true;  // no sample ray within a hair of grazing the sphere
            for (int s = 0; s < 4; ++s) {
                const glm::vec3 d = rays.direction(x, y, offsets[s]);
                const glm::dvec3 oc = glm::dvec3(camera.eye);
                const double b = glm::dot(glm::dvec3(d), oc), disc = b * b - (glm::dot(oc, oc) - 1.0);
                hits += disc > 0.0;
                clear &= std::fabs(disc) > 1e-3;
            }
            // All sky, or all sphere at distances well within the edge test's jump.
            bool uniform = true;
            const float t = rays.distance_from_depth(x, y, one.depth[p]);
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    const float tn = rays.distance_from_depth(x + dx, y + dy, one.depth[p + dy * W + dx]);
                    uniform &= std::isinf(t) ? std::isinf(tn) : std::fabs(tn - t) < t / 32.0f;
                }
            if (uniform) {
                kept += std::memcmp(&one.colour[p], &four.colour[p], sizeof(glm::vec4)) == 0;
                EXPECT_EQ(std::memcmp(&one.colour[p], &four.colour[p], sizeof(glm::vec4)), 0) << x << "," << y;
            }
            if (!clear || hits == 0 || hits == 4) continue;
            ++partial;
            // The surface's share: what is left after the sky's (4 - hits) quarters, per hit,
            // against the one-sample surface colour of a neighbour whose centre hits.
            const glm::vec4 surface = (four.colour[p] - sky * (float(4 - hits) / 4.0f)) * (4.0f / float(hits));
            float nearest = 1e9f;
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx)
                    if (one.depth[p + dy * W + dx] < 1.0f) {
                        const glm::vec4 d = glm::abs(one.colour[p + dy * W + dx] - surface);
                        nearest = std::min(nearest, std::max(std::max(d.r, d.g), d.b));
                    }
            EXPECT_LT(nearest, 0.1f) << x << "," << y << " with " << hits << " of 4 samples on the sphere";
            EXPECT_NE(four.colour[p], sky) << x << "," << y;
            EXPECT_NE(four.colour[p], one.colour[p]) << x << "," << y;
        }
    EXPECT_GT(partial, 12);
    EXPECT_GT(kept, W * H / 3);
}

// The silhouette samples in lanes against the ray-by-ray reference, bit for bit: the sphere
// and metaballs (whose tiles are culled by their centres, while rings and samples reach past
// them) over a half "rasterized" frame, in overlapping rectangles, some pixels in no layer and
// some with only part of their samples.
TEST(MarchPass, SilhouetteSamplesInLanesEqualTheRayByRayReference) {
    const Camera camera = march_camera(W, H);
    const RayGenerator rays(camera, W, H);
    const scene::Background env = sky_background();
    Frame start;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W / 2; ++x) {
            const glm::vec3 d = rays.direction(x, y);
            start.depth[y * W + x] = rays.window_depth(camera.eye + d * ((0.3f - camera.eye.z) / d.z));
            start.colour[y * W + x] = glm::vec4(0.0f, 1.0f, 0.0f, 1.0f);
        }
    std::vector<uint8_t> coverage(size_t(W) * H);
    std::vector<uint16_t> masks(size_t(W) * H);
    for (size_t i = 0; i < masks.size(); ++i) {
        masks[i] = i % 7 == 0 ? 0 : i % 5 == 0 ? uint16_t(0x5) : i % 3 == 0 ? uint16_t(0x8) : uint16_t(0xF);
        coverage[i] = uint8_t(std::popcount(unsigned(masks[i])));
    }
    const auto check = [&](const auto& pass, const char* what) {
        Frame lanes = start, one = start;
        for (const TileRect r : {TileRect{0, 0, W, H}, TileRect{5, 3, 38, 29}}) {
            pass.run(multisampled_tile(lanes, r, coverage.data(), masks.data()));
            pass.run_reference(multisampled_tile(one, r, coverage.data(), masks.data()));
        }
        ASSERT_EQ(std::memcmp(lanes.depth.data(), one.depth.data(), sizeof(float) * W * H), 0) << what;
        ASSERT_EQ(std::memcmp(lanes.colour.data(), one.colour.data(), sizeof(glm::vec4) * W * H), 0) << what;
    };
    check(sphere_pass(rays, env), "sphere");
    const MetaballField balls(orbiting_metaballs(5, 0.8f, 0.9f), MetaballStyle{MetaballKernel::wyvill, 0.4f});
    check(SurfacePass<MetaballSurface>(MetaballSurface{balls}, rays, MarchSettings{}, SurfaceLook{}, env), "metaballs");
}
