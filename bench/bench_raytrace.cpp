// Rasterization against Embree ray tracing on identical work: the sphere-grid scene of
// research/rasterizer-anchors.md 3.2 at a chosen triangle count, resolution, light count and
// thread count. Every benchmark reports wall time (UseRealTime: the work runs on oneTBB).
//
// Arguments, in order: triangles, image height (width = 16/9 of it), lights, threads. Names
// read e.g. "BM_EmbreePrimary/100000/1080/0/2".
//
//   bench_raytrace --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
//
// On a shared machine the wall times carry other processes' load; with threads = 1 the whole
// frame runs on the benchmark's thread, so its CPU time is the cleaner figure to compare.
// (Rate counters - Mrays/s, Mprims/s - are computed from wall time.)
//
// Scenes (mesh, BVH, visibility buffers) are built once per configuration and cached: a 4M-
// triangle scene costs seconds to generate and build, which only the BVH benchmarks time.
#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include <chrono>
#include <map>
#include <memory>
#include <tuple>
#include <vector>

#include "raster/embree/ray_cast.h"
#include "raster/embree/scene.h"
#include "raster/embree/shadow_rays.h"
#include "raster/pipeline/rasterizer.h"
#include "raster/shadow/light_mask.h"
#include "raster/shadow/shadow_map.h"
#include "raster/workloads/sphere_grid.h"

namespace {

using namespace tessera;

struct Fixture {
    workloads::SphereGridScene grid;
    std::unique_ptr<embree::RayScene> scene;
};

Fixture& fixture(int64_t triangles) {
    static std::map<int64_t, std::unique_ptr<Fixture>> cache;
    auto& slot = cache[triangles];
    if (!slot) {
        slot = std::make_unique<Fixture>();
        slot->grid = workloads::make_sphere_grid(size_t(triangles));
        slot->scene = std::make_unique<embree::RayScene>(embree::default_ray_device(), slot->grid.mesh);
    }
    return *slot;
}

int width_for(int64_t height) { return int(height * 16 / 9); }

glm::mat4 view_projection(const Fixture& f, int64_t height) {
    Camera camera = f.grid.camera;
    camera.aspect = float(width_for(height)) / float(height);
    return camera.view_projection();
}

// The rasterizer's visibility buffer of a configuration, cached: the shadow benchmarks
// start from it.
const VisibilityBuffer& visibility(int64_t triangles, int64_t height) {
    static std::map<std::pair<int64_t, int64_t>, VisibilityBuffer> cache;
    auto [it, fresh] = cache.try_emplace({triangles, height});
    if (fresh) {
        const Fixture& f = fixture(triangles);
        pipeline::Rasterizer rasterizer;
        rasterizer.render(f.grid.mesh, view_projection(f, height),
                          pipeline::Viewport(width_for(height), int(height)), pipeline::RasterOptions{}, it->second);
    }
    return it->second;
}

// Up to four lights around the grid, all above it so each casts shadows.
std::vector<glm::vec3> lights(const Fixture& f, int64_t count) {
    const float e = float(f.grid.grid);
    const std::vector<glm::vec3> all = {f.grid.light, {-0.7f * e, 1.2f * e, 0.4f * e},
                                        {0.2f * e, 1.8f * e, -0.8f * e},
                                        {-0.3f * e, 1.0f * e, 1.0f * e}};
    return {all.begin(), all.begin() + count};
}

std::unique_ptr<tbb::global_control> cap_threads(int64_t threads) {
    return std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                 size_t(threads));
}

void set_rays(benchmark::State& state, double rays_per_iteration) {
    state.counters["Mrays/s"] = benchmark::Counter(rays_per_iteration * 1e-6,
                                                   benchmark::Counter::kIsIterationInvariantRate);
}

// --- Primary visibility ----------------------------------------------------------------------

void BM_RasterVisibility(benchmark::State& state) {
    const int64_t tris = state.range(0), height = state.range(1);
    Fixture& f = fixture(tris);
    const glm::mat4 vp = view_projection(f, height);
    const auto cap = cap_threads(state.range(3));
    pipeline::Rasterizer rasterizer;
    VisibilityBuffer vis;
    for (auto _ : state) {
        rasterizer.render(f.grid.mesh, vp, pipeline::Viewport(width_for(height), int(height)),
                          pipeline::RasterOptions{}, vis);
        benchmark::DoNotOptimize(vis.triangle.data());
    }
    state.counters["triangles"] = double(f.grid.mesh.triangle_count());
}

void primary(benchmark::State& state, embree::RayPacket packet) {
    const int64_t tris = state.range(0), height = state.range(1);
    Fixture& f = fixture(tris);
    const glm::mat4 vp = view_projection(f, height);
    const auto cap = cap_threads(state.range(3));
    VisibilityBuffer vis;
    for (auto _ : state) {
        embree::cast_primary_rays(*f.scene, vp, width_for(height), int(height), vis, packet);
        benchmark::DoNotOptimize(vis.triangle.data());
    }
    set_rays(state, double(width_for(height)) * double(height));
    state.counters["triangles"] = double(f.grid.mesh.triangle_count());
}

void BM_EmbreePrimary(benchmark::State& state) { primary(state, embree::RayPacket::x16); }
void BM_EmbreePrimary8(benchmark::State& state) { primary(state, embree::RayPacket::x8); }
void BM_EmbreePrimarySingle(benchmark::State& state) { primary(state, embree::RayPacket::single); }

// --- Shadows from a visibility buffer ----------------------------------------------------------

// Gathering the surface points of every covered pixel (shared by every shadow method): the
// light-mask pass with no lights.
void BM_SurfaceGather(benchmark::State& state) {
    const int64_t tris = state.range(0), height = state.range(1);
    Fixture& f = fixture(tris);
    const VisibilityBuffer& vis = visibility(tris, height);
    const glm::mat4 vp = view_projection(f, height);
    const auto cap = cap_threads(state.range(3));
    for (auto _ : state) {
        const auto mask =
            shadow::compute_light_mask(vis, f.grid.mesh, vp, {}, shadow::facing_lights);
        benchmark::DoNotOptimize(mask.bits.data());
    }
}

constexpr int kShadowMapSize = 2048;

// Shadow maps: one 2048^2 depth-only render per light by the rasterizer, then the PCF lookups
// (each includes gathering the surface points, as the shadow-ray benchmarks do). The maps live
// across frames, as in a renderer; `render_maps` false times the lookups alone.
void shadow_maps(benchmark::State& state, bool render_maps) {
    const int64_t tris = state.range(0), height = state.range(1);
    Fixture& f = fixture(tris);
    const VisibilityBuffer& vis = visibility(tris, height);
    const glm::mat4 vp = view_projection(f, height);
    const std::vector<glm::vec3> light_list = lights(f, state.range(2));
    const auto cap = cap_threads(state.range(3));
    pipeline::Rasterizer rasterizer;
    shadow::ShadowMapOptions options;
    options.resolution = kShadowMapSize;
    std::vector<shadow::ShadowMap> maps;
    for (const glm::vec3& light : light_list)
        maps.emplace_back(rasterizer, f.grid.mesh, light, options);
    for (auto _ : state) {
        if (render_maps)
            for (size_t l = 0; l < maps.size(); ++l) maps[l].render(rasterizer, f.grid.mesh, light_list[l]);
        const auto mask = shadow::compute_light_mask(vis, f.grid.mesh, vp, light_list,
                                                     shadow::shadow_map_test(maps));
        benchmark::DoNotOptimize(mask.bits.data());
    }
}
void BM_ShadowMaps(benchmark::State& state) { shadow_maps(state, true); }
void BM_ShadowMapLookups(benchmark::State& state) { shadow_maps(state, false); }

// The depth render alone, at map resolution range(1) x range(1).
void BM_ShadowMapRender(benchmark::State& state) {
    Fixture& f = fixture(state.range(0));
    const auto cap = cap_threads(state.range(3));
    pipeline::Rasterizer rasterizer;
    shadow::ShadowMapOptions options;
    options.resolution = int(state.range(1));
    shadow::ShadowMap map(rasterizer, f.grid.mesh, f.grid.light, options);
    for (auto _ : state) {
        map.render(rasterizer, f.grid.mesh, f.grid.light);
        benchmark::DoNotOptimize(map.depth().data());
    }
}

void shadow_rays(benchmark::State& state, embree::RayPacket packet) {
    const int64_t tris = state.range(0), height = state.range(1);
    Fixture& f = fixture(tris);
    const VisibilityBuffer& vis = visibility(tris, height);
    const glm::mat4 vp = view_projection(f, height);
    const std::vector<glm::vec3> light_list = lights(f, state.range(2));
    const auto cap = cap_threads(state.range(3));
    const shadow::LightTest test = embree::shadow_ray_test(*f.scene, packet);
    for (auto _ : state) {
        const auto mask = shadow::compute_light_mask(vis, f.grid.mesh, vp, light_list, test);
        benchmark::DoNotOptimize(mask.bits.data());
    }
    size_t covered = 0;
    for (uint32_t id : vis.triangle) covered += id != kNoTriangle;
    set_rays(state, double(covered) * double(light_list.size()));  // upper bound: facing only
}

void BM_EmbreeShadowRays(benchmark::State& state) { shadow_rays(state, embree::RayPacket::x16); }
void BM_EmbreeShadowRays8(benchmark::State& state) { shadow_rays(state, embree::RayPacket::x8); }
void BM_EmbreeShadowRaysSingle(benchmark::State& state) {
    shadow_rays(state, embree::RayPacket::single);
}

// A rasterized frame with shadows: visibility by the rasterizer, then shadow maps (2048^2)
// or Embree shadow rays (BVH prebuilt) to every light.
void raster_frame(benchmark::State& state, bool rays) {
    const int64_t tris = state.range(0), height = state.range(1);
    Fixture& f = fixture(tris);
    const glm::mat4 vp = view_projection(f, height);
    const std::vector<glm::vec3> light_list = lights(f, state.range(2));
    const auto cap = cap_threads(state.range(3));
    pipeline::Rasterizer rasterizer;
    VisibilityBuffer vis;
    shadow::ShadowMapOptions options;
    options.resolution = kShadowMapSize;
    const shadow::LightTest ray_test = embree::shadow_ray_test(*f.scene);
    std::vector<shadow::ShadowMap> maps;
    if (!rays)
        for (const glm::vec3& light : light_list)
            maps.emplace_back(rasterizer, f.grid.mesh, light, options);
    for (auto _ : state) {
        rasterizer.render(f.grid.mesh, vp, pipeline::Viewport(width_for(height), int(height)),
                          pipeline::RasterOptions{}, vis);
        for (size_t l = 0; l < maps.size(); ++l)
            maps[l].render(rasterizer, f.grid.mesh, light_list[l]);
        const auto mask = shadow::compute_light_mask(
            vis, f.grid.mesh, vp, light_list, rays ? ray_test : shadow::shadow_map_test(maps));
        benchmark::DoNotOptimize(mask.bits.data());
    }
}

void BM_RasterFrameShadowMaps(benchmark::State& state) { raster_frame(state, false); }
void BM_RasterFrameShadowRays(benchmark::State& state) { raster_frame(state, true); }

// The whole ray-cast frame: primary rays, then shadow rays to every light.
void BM_EmbreeFrame(benchmark::State& state) {
    const int64_t tris = state.range(0), height = state.range(1);
    Fixture& f = fixture(tris);
    const glm::mat4 vp = view_projection(f, height);
    const std::vector<glm::vec3> light_list = lights(f, state.range(2));
    const auto cap = cap_threads(state.range(3));
    const shadow::LightTest test = embree::shadow_ray_test(*f.scene);
    VisibilityBuffer vis;
    for (auto _ : state) {
        embree::cast_primary_rays(*f.scene, vp, width_for(height), int(height), vis);
        const auto mask = shadow::compute_light_mask(vis, f.grid.mesh, vp, light_list, test);
        benchmark::DoNotOptimize(mask.bits.data());
    }
}

// --- BVH build and per-frame update --------------------------------------------------------

void build(benchmark::State& state, embree::BvhUpdate quality) {
    Fixture& f = fixture(state.range(0));
    const auto cap = cap_threads(state.range(3));
    for (auto _ : state) {
        const embree::RayScene scene(embree::default_ray_device(), f.grid.mesh, quality);
        benchmark::DoNotOptimize(scene.handle());
    }
    state.counters["Mprims/s"] =
        benchmark::Counter(double(f.grid.mesh.triangle_count()) * 1e-6,
                           benchmark::Counter::kIsIterationInvariantRate);
}

// A fresh MEDIUM-quality build (static scenes) and a LOW-quality one (the rebuild option).
void BM_BvhBuildMedium(benchmark::State& state) { build(state, embree::BvhUpdate::none); }
void BM_BvhBuildLow(benchmark::State& state) { build(state, embree::BvhUpdate::rebuild); }

// One animation step: move the vertices (not timed), then refit or rebuild the BVH.
void update(benchmark::State& state, embree::BvhUpdate mode) {
    Fixture& f = fixture(state.range(0));
    workloads::SphereGridScene grid = f.grid;  // a private copy: the animation moves its vertices
    embree::reserve_ray_padding(grid.mesh);
    const auto cap = cap_threads(state.range(3));
    embree::RayScene scene(embree::default_ray_device(), grid.mesh, mode);
    float time = 0.0f;
    for (auto _ : state) {
        state.PauseTiming();
        workloads::ripple_spheres(grid, time += 0.04f);
        state.ResumeTiming();
        scene.update();
    }
    state.counters["Mprims/s"] =
        benchmark::Counter(double(grid.mesh.triangle_count()) * 1e-6,
                           benchmark::Counter::kIsIterationInvariantRate);
}

// The defect scan every update() repeats (NaN / bad index / zero-area triangles), part of
// the refit and rebuild times above.
void BM_MeshDefects(benchmark::State& state) {
    Fixture& f = fixture(state.range(0));
    const auto cap = cap_threads(state.range(3));
    for (auto _ : state) benchmark::DoNotOptimize(embree::find_mesh_defects(f.grid.mesh));
}

void BM_BvhRefit(benchmark::State& state) { update(state, embree::BvhUpdate::refit); }
void BM_BvhRebuild(benchmark::State& state) { update(state, embree::BvhUpdate::rebuild); }

// One animated frame: move the vertices (not timed), update the BVH, find visibility (Embree
// primary rays, or the rasterizer) and trace shadow rays. Reports the update's share of the
// timed frame (the "refit <= 10%" target).
void animated_frame(benchmark::State& state, embree::BvhUpdate mode, bool rasterize) {
    const int64_t height = state.range(1);
    Fixture& f = fixture(state.range(0));
    workloads::SphereGridScene grid = f.grid;
    embree::reserve_ray_padding(grid.mesh);
    const auto cap = cap_threads(state.range(3));
    embree::RayScene scene(embree::default_ray_device(), grid.mesh, mode);
    const glm::mat4 vp = view_projection(f, height);
    const std::vector<glm::vec3> light_list = lights(f, state.range(2));
    const shadow::LightTest test = embree::shadow_ray_test(scene);
    VisibilityBuffer vis;
    pipeline::Rasterizer rasterizer;
    using clock = std::chrono::steady_clock;
    double update_s = 0.0, frame_s = 0.0;
    float time = 0.0f;
    for (auto _ : state) {
        state.PauseTiming();
        workloads::ripple_spheres(grid, time += 0.04f);
        state.ResumeTiming();
        const auto start = clock::now();
        scene.update();
        const auto updated = clock::now();
        if (rasterize)
            rasterizer.render(grid.mesh, vp, pipeline::Viewport(width_for(height), int(height)),
                              pipeline::RasterOptions{}, vis);
        else
            embree::cast_primary_rays(scene, vp, width_for(height), int(height), vis);
        const auto mask = shadow::compute_light_mask(vis, grid.mesh, vp, light_list, test);
        benchmark::DoNotOptimize(mask.bits.data());
        update_s += std::chrono::duration<double>(updated - start).count();
        frame_s += std::chrono::duration<double>(clock::now() - start).count();
    }
    state.counters["update_ms"] =
        benchmark::Counter(update_s * 1e3, benchmark::Counter::kAvgIterations);
    state.counters["update_share"] = update_s / frame_s;
}

void BM_AnimatedFrameRefit(benchmark::State& state) {
    animated_frame(state, embree::BvhUpdate::refit, false);
}
void BM_AnimatedFrameRebuild(benchmark::State& state) {
    animated_frame(state, embree::BvhUpdate::rebuild, false);
}
void BM_AnimatedRasterFrameRefit(benchmark::State& state) {
    animated_frame(state, embree::BvhUpdate::refit, true);
}
void BM_AnimatedRasterFrameRebuild(benchmark::State& state) {
    animated_frame(state, embree::BvhUpdate::rebuild, true);
}

// --- Sweeps ------------------------------------------------------------------------------------

constexpr int64_t kTriangleCounts[] = {1000, 16000, 100000, 1000000, 4000000};
constexpr int64_t kHeights[] = {720, 1080, 2160, 4320};

// Triangle sweep at 1080p, one light, 1 and 2 threads.
void triangle_sweep(benchmark::internal::Benchmark* b) {
    for (int64_t threads : {1, 2})
        for (int64_t tris : kTriangleCounts) b->Args({tris, 1080, 1, threads});
}

// Resolution sweep at 100k triangles, one light, 2 threads.
void resolution_sweep(benchmark::internal::Benchmark* b) {
    for (int64_t height : kHeights) b->Args({100000, height, 1, 2});
}

// Light sweep at 100k triangles, 1080p, 2 threads.
void light_sweep(benchmark::internal::Benchmark* b) {
    for (int64_t lights = 0; lights <= 4; ++lights) b->Args({100000, 1080, lights, 2});
}

// The packet-width comparison: 1080p, one light, one thread, small and large scenes.
void packet_sweep(benchmark::internal::Benchmark* b) {
    for (int64_t tris : {16000, 100000, 1000000}) b->Args({tris, 1080, 1, 1});
}

// Shadow-map depth render at 1024^2 .. 4096^2, 100k triangles, 1 and 2 threads.
void map_sweep(benchmark::internal::Benchmark* b) {
    for (int64_t threads : {1, 2})
        for (int64_t size : {1024, 2048, 4096}) b->Args({100000, size, 1, threads});
}

void bvh_sweep(benchmark::internal::Benchmark* b) {
    for (int64_t threads : {1, 2})
        for (int64_t tris : kTriangleCounts) b->Args({tris, 0, 0, threads});
}

#define TESSERA_SWEEP(bench, sweep) \
    BENCHMARK(bench)->Apply(sweep)->UseRealTime()->Unit(benchmark::kMillisecond)

TESSERA_SWEEP(BM_RasterVisibility, triangle_sweep);
TESSERA_SWEEP(BM_RasterVisibility, resolution_sweep);
TESSERA_SWEEP(BM_EmbreePrimary, triangle_sweep);
TESSERA_SWEEP(BM_EmbreePrimary, resolution_sweep);
TESSERA_SWEEP(BM_EmbreePrimary8, packet_sweep);
TESSERA_SWEEP(BM_EmbreePrimarySingle, packet_sweep);
TESSERA_SWEEP(BM_SurfaceGather, triangle_sweep);
TESSERA_SWEEP(BM_ShadowMaps, triangle_sweep);
TESSERA_SWEEP(BM_ShadowMaps, light_sweep);
TESSERA_SWEEP(BM_ShadowMapLookups, triangle_sweep);
TESSERA_SWEEP(BM_ShadowMapRender, map_sweep);
TESSERA_SWEEP(BM_EmbreeShadowRays, triangle_sweep);
TESSERA_SWEEP(BM_EmbreeShadowRays, light_sweep);
TESSERA_SWEEP(BM_EmbreeShadowRays, resolution_sweep);
TESSERA_SWEEP(BM_EmbreeShadowRays8, packet_sweep);
TESSERA_SWEEP(BM_EmbreeShadowRaysSingle, packet_sweep);
TESSERA_SWEEP(BM_RasterFrameShadowMaps, triangle_sweep);
TESSERA_SWEEP(BM_RasterFrameShadowMaps, light_sweep);
TESSERA_SWEEP(BM_RasterFrameShadowRays, triangle_sweep);
TESSERA_SWEEP(BM_RasterFrameShadowRays, light_sweep);
TESSERA_SWEEP(BM_EmbreeFrame, triangle_sweep);
TESSERA_SWEEP(BM_EmbreeFrame, light_sweep);
TESSERA_SWEEP(BM_BvhBuildMedium, bvh_sweep);
TESSERA_SWEEP(BM_BvhBuildLow, bvh_sweep);
TESSERA_SWEEP(BM_MeshDefects, bvh_sweep);
TESSERA_SWEEP(BM_BvhRefit, bvh_sweep);
TESSERA_SWEEP(BM_BvhRebuild, bvh_sweep);
TESSERA_SWEEP(BM_AnimatedFrameRefit, triangle_sweep);
TESSERA_SWEEP(BM_AnimatedFrameRebuild, triangle_sweep);
TESSERA_SWEEP(BM_AnimatedRasterFrameRefit, triangle_sweep);
TESSERA_SWEEP(BM_AnimatedRasterFrameRebuild, triangle_sweep);

}  // namespace
