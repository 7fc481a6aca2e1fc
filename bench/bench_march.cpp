// Ray-marching throughput, one thread (BM_MarchFrame: all cores): rays per second for each field and step strategy over
// a 256x144 view (the scalar reference next to the packet path), the surface pass of the
// terrain and metaball scenes in lanes and one ray at a time, the cost of normals, and the
// per-pixel cost of fog and background. Compare rates within one run (the machine is
// shared); items_per_second is rays (or pixels) per second.
#include <benchmark/benchmark.h>

#include <vector>

#include "procedural/field.h"
#include "raster/march/background_pass.h"
#include "raster/march/fog_pass.h"
#include "raster/march/march_scene.h"
#include "raster/march/metaball_orbits.h"
#include "raster/march/procedural_surfaces.h"
#include "raster/march/sphere_field.h"
#include "raster/march/surface_normal.h"
#include "raster/march/surface_pass.h"
#include "raster/pipeline/rasterizer.h"

using namespace tessera;
using namespace tessera::march;

namespace {

constexpr int W = 256, H = 144;

Camera view(glm::vec3 eye, glm::vec3 lookat, float far = 100.0f) {
    Camera c;
    c.eye = eye;
    c.lookat = lookat;
    c.aspect = float(W) / float(H);
    c.far = far;
    return c;
}

MarchSettings strategy(int geometric) {
    MarchSettings s;
    s.strategy = geometric ? StepStrategy::geometric : StepStrategy::uniform;
    return s;
}

// Binds every packet of the view to the surface and counts the hits `march(field, packet,
// segments)` reports for it (kept so nothing is optimised away).
template <class Surface, class March>
int count_hits(const Surface& surface, const RayGenerator& rays, float t_far, March march) {
    typename Surface::Scratch scratch{};
    int hits = 0;
    for (int y = 0; y < H; ++y)
        for (int x0 = 0; x0 < W; x0 += kMarchLanes) {
            RayPacket packet;
            rays.packet(x0, y, kMarchLanes, packet);
            PacketSegments segments;
            const auto& field = surface.bind(packet, t_far, segments, scratch);
            hits += march(field, packet, segments);
        }
    return hits;
}

// The whole view in packets.
template <class Surface>
int march_view(const Surface& surface, const RayGenerator& rays, const MarchSettings& settings, float t_far) {
    return count_hits(surface, rays, t_far, [&](const auto& field, const RayPacket& packet,
                                                const PacketSegments& segments) {
        alignas(64) float t[kMarchLanes];
        march_packet(field, packet, segments, settings, t);
        int hits = 0;
        for (int i = 0; i < kMarchLanes; ++i) hits += t[i] != kMiss;
        return hits;
    });
}

// The scalar reference: one ray at a time through march_ray.
template <class Surface>
int march_view_scalar(const Surface& surface, const RayGenerator& rays, const MarchSettings& settings, float t_far) {
    return count_hits(surface, rays, t_far, [&](const auto& field, const RayPacket& packet,
                                                const PacketSegments& segments) {
        int hits = 0;
        for (int i = 0; i < kMarchLanes; ++i)
            hits += march_ray(field, packet.origin(i), packet.direction(i), Interval{segments.t0[i], segments.t1[i]},
                              settings) != kMiss;
        return hits;
    });
}

template <class Surface>
void run(benchmark::State& state, const Surface& surface, const Camera& camera, float t_far) {
    const RayGenerator rays(camera, W, H);
    const MarchSettings settings = strategy(int(state.range(0)));
    const bool packet = state.range(1) != 0;
    int hits = 0;
    for (auto _ : state) {
        hits = packet ? march_view(surface, rays, settings, t_far) : march_view_scalar(surface, rays, settings, t_far);
        benchmark::DoNotOptimize(hits);
    }
    state.SetItemsProcessed(state.iterations() * W * H);
    state.counters["hit_fraction"] = double(hits) / (W * H);
}

// Arguments: {geometric?, packet?}.
void strategies(benchmark::internal::Benchmark* b) {
    b->ArgNames({"geometric", "packet"});
    for (int g : {0, 1})
        for (int p : {0, 1}) b->Args({g, p});
}

void BM_MarchSphere(benchmark::State& state) {
    const SphereField sphere{{0.0f, 0.0f, 0.0f}, 1.0f};
    run(state, SlabSurface<SphereField>{sphere, Slab{-1.0f, 1.0f}}, view({0.5f, 0.4f, 3.5f}, {0, 0, 0}), 10.0f);
}
BENCHMARK(BM_MarchSphere)->Apply(strategies);

void metaballs(benchmark::State& state, MetaballKernel kernel, int count) {
    const MetaballField field(orbiting_metaballs(count, 0.8f), MetaballStyle{kernel, 0.5f});
    run(state, MetaballSurface{field}, view({0.0f, 0.6f, 4.0f}, {0, 0, 0}), 20.0f);
}
void BM_MarchMetaballsBlinn(benchmark::State& s) { metaballs(s, MetaballKernel::blinn, 3); }
void BM_MarchMetaballsPerlin(benchmark::State& s) { metaballs(s, MetaballKernel::perlin, 3); }
void BM_MarchMetaballsWyvill(benchmark::State& s) { metaballs(s, MetaballKernel::wyvill, 3); }
BENCHMARK(BM_MarchMetaballsBlinn)->Apply(strategies);
BENCHMARK(BM_MarchMetaballsPerlin)->Apply(strategies);
BENCHMARK(BM_MarchMetaballsWyvill)->Apply(strategies);

// 3 visible balls plus 61 far ones out of view: culling should make the cost close to 3 balls.
void BM_MarchMetaballsWyvillFarBalls(benchmark::State& state) {
    std::vector<Metaball> balls = orbiting_metaballs(3, 0.8f);
    for (int i = 0; i < 61; ++i) balls.push_back({{30.0f + float(i), 0.0f, -5.0f}, 1.0f, 1.0f});
    const MetaballField field(balls, MetaballStyle{MetaballKernel::wyvill, 0.5f});
    run(state, MetaballSurface{field}, view({0.0f, 0.6f, 4.0f}, {0, 0, 0}), 20.0f);
}
BENCHMARK(BM_MarchMetaballsWyvillFarBalls)->Args({0, 1})->ArgNames({"geometric", "packet"});

void BM_MarchTerrain(benchmark::State& state) {
    const procedural::TerrainField terrain(procedural::TerrainParams{});
    run(state, terrain_surface(terrain), view({0.0f, 1.6f, 0.0f}, {60.0f, 0.2f, 40.0f}, 400.0f), 400.0f);
}
BENCHMARK(BM_MarchTerrain)->Apply(strategies);

void BM_MarchSineNoise(benchmark::State& state) {
    const procedural::SineNoiseField noise;
    run(state, sine_noise_surface(noise), view({0.0f, 1.3f, 3.0f}, {0.5f, 0.4f, 0.0f}, 40.0f), 40.0f);
}
BENCHMARK(BM_MarchSineNoise)->Apply(strategies);

void BM_MarchNoiseVolume(benchmark::State& state) {
    const procedural::NoiseVolumeField volume(procedural::VolumeParams{});
    run(state, noise_volume_surface(volume), view({0.0f, 1.5f, 4.0f}, {0.0f, 0.3f, 0.0f}, 40.0f), 40.0f);
}
BENCHMARK(BM_MarchNoiseVolume)->Apply(strategies);

void BM_MarchGradientNoise(benchmark::State& state) {
    const GradientNoiseField noise;
    run(state, gradient_noise_surface(noise), view({0.0f, 1.5f, 4.0f}, {0.0f, 0.3f, 0.0f}, 40.0f), 40.0f);
}
BENCHMARK(BM_MarchGradientNoise)->Apply(strategies);

// Normals at a point: analytic gradient vs central differences (h = 0.05).
void BM_TerrainNormal(benchmark::State& state) {
    const procedural::TerrainField terrain(procedural::TerrainParams{});
    const NormalSettings settings{state.range(0) ? NormalMethod::central_differences : NormalMethod::analytic, 0.05f};
    glm::vec3 p(1.0f, 0.5f, 2.0f);
    for (auto _ : state) {
        const glm::vec3 n = surface_normal(terrain, p, settings);
        benchmark::DoNotOptimize(n);
        p.x += 0.01f;
    }
    state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_TerrainNormal)->Arg(0)->Arg(1)->ArgName("central_differences");

// Per-pixel cost of the fog pass: half the view at finite depth, half background.
void BM_FogPass(benchmark::State& state) {
    const RayGenerator rays(view({0.0f, 1.0f, 4.0f}, {0, 0, 0}), W, H);
    Fog fog;
    fog.density = {0.05f, 0.06f, 0.08f};
    fog.colour = {0.6f, 0.65f, 0.7f};
    fog.falloff = state.range(0) ? 0.7f : 0.0f;
    const FogPass pass(rays, fog);
    std::vector<float> depth(W * H);
    std::vector<glm::vec4> colour(W * H, glm::vec4(0.5f));
    for (int i = 0; i < W * H; ++i) depth[i] = i % W < W / 2 ? 0.97f : 1.0f;
    const Tile target{{0, 0, W, H}, nullptr, depth.data(), W, colour.data(), W};
    for (auto _ : state) {
        pass.run(target);
        benchmark::DoNotOptimize(colour.data());
    }
    state.SetItemsProcessed(state.iterations() * W * H);
}
BENCHMARK(BM_FogPass)->Arg(0)->Arg(1)->ArgName("height");

void BM_BackgroundSky(benchmark::State& state) {
    const RayGenerator rays(view({0.0f, 1.0f, 4.0f}, {0, 0, 0}), W, H);
    scene::Background sky;
    sky.kind = scene::Background::Kind::sky;
    const BackgroundPass pass(rays, sky);
    std::vector<float> depth(W * H, 1.0f);
    std::vector<glm::vec4> colour(W * H);
    const Tile target{{0, 0, W, H}, nullptr, depth.data(), W, colour.data(), W};
    for (auto _ : state) {
        pass.run(target);
        benchmark::DoNotOptimize(colour.data());
    }
    state.SetItemsProcessed(state.iterations() * W * H);
}
BENCHMARK(BM_BackgroundSky);

// The surface pass as the built-in scenes run it, on a 256x144 view in 64x64 tiles, one
// thread: args {scene (0 terrain: ridged relief, 5 octaves, geometric steps; 1 metaballs: 7
// Wyvill balls, 96 uniform steps, a mirror term), lanes?}. Lanes is SurfacePass::run (the
// packet march, bounds, normals and shading in lanes, tile culling), the other
// run_reference (one ray at a time through march_ray, one hit at a time). items = pixels.
void BM_SurfacePass(benchmark::State& state) {
    const bool terrain = state.range(0) == 0, lanes = state.range(1) != 0;
    procedural::TerrainParams relief;
    relief.relief = procedural::Relief::ridged;
    relief.fractal = {5, 2.0f, 0.5f, 3};
    relief.frequency = 0.12f;
    relief.amplitude = 1.6f;
    relief.base = -0.4f;
    const procedural::TerrainField field(relief);
    std::vector<Metaball> balls = orbiting_metaballs(7, 1.0f, 0.9f);
    for (Metaball& b : balls) b.centre *= 1.1f;
    const MetaballField metaballs(balls, MetaballStyle{MetaballKernel::wyvill, 0.35f});
    MarchSettings settings;
    SurfaceLook look;
    if (terrain) {
        settings.strategy = StepStrategy::geometric;
        settings.tolerance = 5e-4f;
    } else {
        settings.steps = 96;
        look.material.reflectivity = 0.25f;
    }
    const Camera camera = terrain ? view({0.0f, 1.2f, 6.0f}, {0.5f, 0.8f, -4.0f}, 80.0f)
                                  : view({0.0f, 0.6f, 4.2f}, {0.0f, 0.0f, 0.0f}, 20.0f);
    const RayGenerator rays(camera, W, H);
    scene::Background sky;
    sky.kind = scene::Background::Kind::sky;
    const SurfacePass terrain_pass(terrain_surface(field), rays, settings, look, sky);
    const SurfacePass<MetaballSurface> metaball_pass(MetaballSurface{metaballs}, rays, settings, look, sky);
    std::vector<float> depth(W * H);
    std::vector<glm::vec4> colour(W * H);
    for (auto _ : state) {
        std::fill(depth.begin(), depth.end(), 1.0f);
        for (int y0 = 0; y0 < H; y0 += 64)
            for (int x0 = 0; x0 < W; x0 += 64) {
                const Tile tile{{x0, y0, std::min(W, x0 + 64), std::min(H, y0 + 64)}, nullptr,
                                depth.data() + y0 * W + x0, W, colour.data() + y0 * W + x0, W};
                if (terrain)
                    lanes ? terrain_pass.run(tile) : terrain_pass.run_reference(tile);
                else
                    lanes ? metaball_pass.run(tile) : metaball_pass.run_reference(tile);
            }
        benchmark::DoNotOptimize(colour.data());
    }
    state.SetItemsProcessed(state.iterations() * W * H);
    int hits = 0;
    for (float d : depth) hits += d < 1.0f;
    state.counters["hit_fraction"] = double(hits) / (W * H);
}
BENCHMARK(BM_SurfacePass)->ArgNames({"scene", "lanes"})->ArgsProduct({{0, 1}, {0, 1}})->Unit(benchmark::kMillisecond);

// A whole frame through the rasterizer's tile stage (tiles in parallel on every core):
// background, marched surface and fog passes, 960x540. Arguments: {scene, fog?}.
void BM_MarchFrame(benchmark::State& state) {
    const march::MarchSceneKind kinds[] = {march::MarchSceneKind::terrain, march::MarchSceneKind::sine_noise,
                                           march::MarchSceneKind::noise_volume, march::MarchSceneKind::metaballs,
                                           march::MarchSceneKind::gradient_noise};
    march::MarchSceneSettings settings;
    settings.kind = kinds[state.range(0)];
    settings.march.strategy = StepStrategy::geometric;
    if (state.range(1)) {
        settings.fog.density = glm::vec3(0.02f);
        settings.fog.colour = glm::vec3(0.7f);
        settings.fog.falloff = 0.3f;
    }
    constexpr int FW = 960, FH = 540;
    const march::MarchScene scene(settings, FW, FH);
    const std::vector<pipeline::TilePass> passes = scene.passes();
    pipeline::Rasterizer rasterizer;
    VisibilityBuffer visibility;
    std::vector<glm::vec4> colour;
    for (auto _ : state) {
        rasterizer.render(Mesh{}, scene.camera().view_projection(), pipeline::Viewport(FW, FH), pipeline::RasterOptions{}, visibility,
                          passes, &colour);
        benchmark::DoNotOptimize(colour.data());
    }
    state.SetItemsProcessed(state.iterations() * FW * FH);
}
BENCHMARK(BM_MarchFrame)
    ->ArgNames({"scene", "fog"})
    ->Args({0, 0})->Args({0, 1})->Args({1, 0})->Args({2, 0})->Args({4, 0})->Args({3, 0})->Args({3, 1})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

}  // namespace
