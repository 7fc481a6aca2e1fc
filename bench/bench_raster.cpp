// Rasterizer benchmarks: per-stage costs (vertex, setup, binning, tile raster) and whole frames
// for 10k .. 4M triangles at 1080p and 4K on 1 and 2 threads, plus a fill-rate test in the
// style of Intel MSOC's FillrateTest (random right triangles, legs of 10/25/50/250 pixels,
// back to front at 1080p, every fragment passes the depth test and writes).
//
// Counters: tri/s and pix/s are rates over wall time (Google Benchmark prints them scaled,
// e.g. 10.2M/s); "pix" counts triangle area (leg^2 / 2), as MSOC does. The CPU column of the
// fill-rate and frame benchmarks is the whole process's CPU time (all threads), so on a busy
// machine CPU/threads bounds what the wall time would be on idle cores.
#include <benchmark/benchmark.h>

#include <tbb/global_control.h>

#include <glm/gtc/matrix_transform.hpp>

#include <map>
#include <memory>

#include "raster/pipeline/bin.h"
#include "raster/core/camera.h"
#include "raster/pipeline/primitive_stage.h"
#include "raster/pipeline/rasterizer.h"
#include "raster/shade/reference_shading.h"
#include "raster/shade/stamp_shading.h"
#include "raster/simd/simd.h"
#include "raster/workloads/sphere_grid.h"
#include "raster/workloads/test_meshes.h"
#include "raster/pipeline/vertex_stage.h"

namespace {

using namespace tessera;

const glm::mat4 kIdentity(1.0f);

// Meshes are generated once per configuration and kept for the whole run.
const Mesh& fill_rate_mesh(int leg, size_t count) {
    static std::map<std::pair<int, size_t>, std::unique_ptr<Mesh>> cache;
    auto& slot = cache[{leg, count}];
    if (!slot)
        slot = std::make_unique<Mesh>(workloads::to_world(
            workloads::fill_rate(7, count, float(leg), 1920, 1080), kIdentity, 1920, 1080));
    return *slot;
}

// A sphere of about `triangles` triangles filling most of the view.
const Mesh& sphere_mesh(size_t triangles) {
    static std::map<size_t, std::unique_ptr<Mesh>> cache;
    auto& slot = cache[triangles];
    if (!slot) {
        const int rings = std::max(4, int(std::sqrt(double(triangles) / 4.0)));
        const int segments = int(triangles / (2 * size_t(rings - 1)));
        slot = std::make_unique<Mesh>(workloads::sphere(segments, rings));
    }
    return *slot;
}

Camera sphere_view(int w, int h) {
    Camera camera;
    camera.eye = {0.0f, 0.4f, 2.6f};
    camera.aspect = float(w) / float(h);
    camera.fovy_deg = 50.0f;
    return camera;
}

glm::mat4 sphere_camera(int w, int h) { return sphere_view(w, h).view_projection(); }

void BM_FillRate(benchmark::State& state) {
    const int leg = int(state.range(0));
    const int threads = int(state.range(1));
    const size_t count = leg <= 25 ? (1u << 20) : leg <= 50 ? (1u << 19) : (1u << 16);
    const Mesh& mesh = fill_rate_mesh(leg, count);
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(threads));
    pipeline::Rasterizer rasterizer;
    VisibilityBuffer vis;
    const pipeline::Viewport viewport(1920, 1080);
    rasterizer.render(mesh, kIdentity, viewport, {}, vis);  // warm-up: allocations, page faults
    for (auto _ : state) {
        rasterizer.render(mesh, kIdentity, viewport, {}, vis);
        benchmark::DoNotOptimize(vis.triangle.data());
    }
    state.counters["tri/s"] = benchmark::Counter(double(count), benchmark::Counter::kIsIterationInvariantRate);
    state.counters["pix/s"] =
        benchmark::Counter(double(count) * leg * leg / 2.0, benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_FillRate)
    ->ArgNames({"leg", "threads"})
    ->ArgsProduct({{10, 25, 50, 250}, {1, 2}})
    ->Unit(benchmark::kMillisecond)
    ->MeasureProcessCPUTime()
    ->UseRealTime();

void BM_Frame(benchmark::State& state) {
    const size_t triangles = size_t(state.range(0)) * 1000;
    const int height = int(state.range(1));
    const int width = height * 16 / 9;
    const int threads = int(state.range(2));
    const Mesh& mesh = sphere_mesh(triangles);
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(threads));
    pipeline::Rasterizer rasterizer;
    VisibilityBuffer vis;
    const pipeline::Viewport viewport(width, height);
    const glm::mat4 vp = sphere_camera(width, height);
    pipeline::RasterOptions options;
    options.cull = pipeline::CullMode::back;
    rasterizer.render(mesh, vp, viewport, options, vis);  // warm-up: allocations, page faults
    for (auto _ : state) {
        rasterizer.render(mesh, vp, viewport, options, vis);
        benchmark::DoNotOptimize(vis.triangle.data());
    }
    state.counters["tri/s"] =
        benchmark::Counter(double(mesh.triangle_count()), benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_Frame)
    ->ArgNames({"ktris", "height", "threads"})
    ->ArgsProduct({{10, 100, 1000, 4000}, {1080, 2160}, {1, 2}})
    ->Unit(benchmark::kMillisecond)
    ->MeasureProcessCPUTime()
    ->UseRealTime();

// A whole 1080p frame of the sphere with the --shade phong pass, 1 thread: the scalar
// reference pass (simd:0) vs the SIMD stamp pass (simd:1); the raster work is the same in both,
// so the difference is the shading.
void BM_FramePhong(benchmark::State& state) {
    const Mesh& mesh = sphere_mesh(size_t(state.range(0)) * 1000);
    const bool simd = state.range(1) != 0;
    const int width = 1920, height = 1080;
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
    const Camera camera = sphere_view(width, height);
    std::vector<uint32_t> rgba8(size_t(width) * height);
    const pipeline::TilePass pass = simd ? shade::make_stamp_shading_pass(shade::ShadeMode::phong, camera, rgba8)
                               : shade::make_reference_shading_pass(shade::ShadeMode::phong, camera, rgba8);
    pipeline::Rasterizer rasterizer;
    VisibilityBuffer vis;
    pipeline::RasterOptions options;
    options.cull = pipeline::CullMode::back;
    options.tile_color = !simd;  // what tessera raster does with each pass
    options.frame_visibility = !simd;
    const pipeline::Viewport viewport(width, height);
    rasterizer.render(mesh, camera.view_projection(), viewport, options, vis, {&pass, 1});  // warm-up
    for (auto _ : state) {
        rasterizer.render(mesh, camera.view_projection(), viewport, options, vis, {&pass, 1});
        benchmark::DoNotOptimize(rgba8.data());
    }
}
BENCHMARK(BM_FramePhong)
    ->ArgNames({"ktris", "simd"})
    ->ArgsProduct({{20, 1000}, {0, 1}})
    ->Unit(benchmark::kMillisecond)
    ->MeasureProcessCPUTime()
    ->UseRealTime();

// tessera raster's frame on the sphere-grid scene (workloads::make_sphere_grid: a ground plane
// under a grid of spheres, most of the 1080p frame covered), 1 thread, --cull none, split by
// stage (mode): 0 visibility only (vertex, setup, binning, tile raster; the visibility stays
// in the tiles, as with the shading passes), 1 --shade id, 2 --shade phong, 3 visibility
// written to the frame's buffer (what --out-id adds). The differences between modes are the
// per-pixel costs of the passes; the counters give them per covered pixel and per triangle.
void BM_FrameSphereGrid(benchmark::State& state) {
    static std::map<size_t, std::unique_ptr<workloads::SphereGridScene>> cache;
    const size_t ktris = size_t(state.range(0));
    auto& slot = cache[ktris];
    if (!slot) slot = std::make_unique<workloads::SphereGridScene>(workloads::make_sphere_grid(ktris * 1000));
    const workloads::SphereGridScene& scene = *slot;
    const int mode = int(state.range(1));
    const int width = 1920, height = 1080;
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
    std::vector<uint32_t> rgba8(size_t(width) * height);
    std::vector<pipeline::TilePass> passes;
    if (mode == 1) passes.push_back(shade::make_stamp_shading_pass(shade::ShadeMode::id, scene.camera, rgba8));
    if (mode == 2) passes.push_back(shade::make_stamp_shading_pass(shade::ShadeMode::phong, scene.camera, rgba8));
    pipeline::Rasterizer rasterizer;
    VisibilityBuffer vis;
    pipeline::RasterOptions options;
    options.tile_color = false;
    options.frame_visibility = mode == 3;
    const pipeline::Viewport viewport(width, height);
    const glm::mat4 vp = scene.camera.view_projection();
    pipeline::RasterStats stats;
    rasterizer.render(scene.mesh, vp, viewport, options, vis, passes, nullptr, &stats);  // warm-up
    for (auto _ : state) {
        rasterizer.render(scene.mesh, vp, viewport, options, vis, passes);
        benchmark::DoNotOptimize(rgba8.data());
    }
    state.counters["tris"] = double(scene.mesh.triangle_count());
    state.counters["covered_px"] = double(stats.visible_pixels);
    state.counters["ns/px"] = benchmark::Counter(1e-9 * double(stats.visible_pixels),
                                                 benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_FrameSphereGrid)
    ->ArgNames({"ktris", "mode"})
    ->ArgsProduct({{10, 100, 1000}, {0, 1, 2, 3}})
    ->Unit(benchmark::kMillisecond)
    ->MeasureProcessCPUTime()
    ->UseRealTime();

// The lane throughput the per-pixel passes are held against: one thread issuing independent
// vfloat operations of one kind (op 0: fma, 1: divide, 2: square root) in eight chains, enough
// to hide each one's latency, so the time per operation is the issue rate of the unit that
// executes it (an add or multiply issues like an fma). Counters: ns/op, CPU time per
// kLanes-wide operation; lane_ops/s, that rate times kLanes. The values stay normal (no
// denormal slow path): the fma chain converges to 1, the divide chain alternates x and 1/x,
// the root chain converges to 1.
void BM_LaneThroughput(benchmark::State& state) {
    using simd::vfloat;
    constexpr int kChains = 8, kSteps = 256;
    const int op = int(state.range(0));
    vfloat x[kChains];
    for (int c = 0; c < kChains; ++c) x[c] = vfloat(1.5f + 0.125f * float(c));
    const vfloat half(0.5f), one(1.0f);
    for (auto _ : state) {
        for (int step = 0; step < kSteps; ++step) {
            for (int c = 0; c < kChains; ++c) {
                switch (op) {
                    case 0: x[c] = simd::fma(x[c], half, half); break;
                    case 1: x[c] = one / x[c]; break;
                    default: x[c] = simd::sqrt(x[c]); break;
                }
            }
        }
        for (int c = 0; c < kChains; ++c) benchmark::DoNotOptimize(x[c]);
    }
    const double ops = double(kChains) * kSteps;
    state.counters["ns/op"] =
        benchmark::Counter(1e-9 * ops, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
    state.counters["lane_ops/s"] = benchmark::Counter(ops * simd::kLanes, benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_LaneThroughput)->ArgName("op")->DenseRange(0, 2);

// The front end alone: vertex stage + clip/cull/setup of one chunk of every triangle.
void BM_Setup(benchmark::State& state) {
    const size_t triangles = size_t(state.range(0)) * 1000;
    const Mesh& mesh = sphere_mesh(triangles);
    const pipeline::Viewport viewport(1920, 1080);
    const glm::mat4 vp = sphere_camera(1920, 1080);
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
    pipeline::ClipVertices vertices;
    std::vector<pipeline::BinItem> items;
    std::vector<pipeline::TriangleSetup> setups;
    pipeline::RasterOptions options;
    options.cull = pipeline::CullMode::back;
    for (auto _ : state) {
        pipeline::run_vertex_stage(mesh, vp, viewport, vertices);
        items.clear();
        setups.clear();
        pipeline::RasterStats stats;
        pipeline::run_primitive_stage(mesh, vertices, viewport, options, 0, uint32_t(mesh.triangle_count()), items,
                                      setups, stats);
        benchmark::DoNotOptimize(items.data());
    }
    state.counters["tri/s"] =
        benchmark::Counter(double(mesh.triangle_count()), benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_Setup)->ArgName("ktris")->Arg(100)->Arg(1000)->Unit(benchmark::kMillisecond)->UseRealTime();

// The back-face-culled triangles of the 1080p sphere frame as one chunk, every setup stored
// (no deferred setups): the input of the binning and tile-stage benchmarks, which measure
// those stages alone.
struct SphereChunk {
    pipeline::ChunkBins chunk;
    std::vector<pipeline::BinItem> items;
    std::vector<pipeline::TriangleSetup> setups;
};
SphereChunk sphere_setups(size_t triangles) {
    const Mesh& mesh = sphere_mesh(triangles);
    const pipeline::Viewport viewport(1920, 1080);
    pipeline::ClipVertices vertices;
    pipeline::run_vertex_stage(mesh, sphere_camera(1920, 1080), viewport, vertices);
    SphereChunk s;
    pipeline::RasterStats stats;
    pipeline::RasterOptions options;
    options.cull = pipeline::CullMode::back;
    pipeline::run_primitive_stage(mesh, vertices, viewport, options, 0, uint32_t(mesh.triangle_count()), s.items,
                                  s.setups, stats, /*store_all=*/true);
    return s;
}

// Binning alone, on the setups of one frame.
void BM_Binning(benchmark::State& state) {
    const size_t triangles = size_t(state.range(0)) * 1000;
    const int tile = int(state.range(1));
    SphereChunk s = sphere_setups(triangles);
    pipeline::ChunkBins& chunk = s.chunk;
    const TileGrid grid(1920, 1080, tile);
    std::vector<uint32_t> scratch;
    for (auto _ : state) {
        chunk.bin(s.items, s.setups, grid, scratch);
        benchmark::DoNotOptimize(chunk.entries.data());
    }
    state.counters["tri/s"] =
        benchmark::Counter(double(s.setups.size()), benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_Binning)
    ->ArgNames({"ktris", "tile"})
    ->ArgsProduct({{100, 1000}, {32, 64, 128}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// The tile stage alone (1 thread, all tiles), for each tile size.
void BM_TileRaster(benchmark::State& state) {
    const size_t triangles = size_t(state.range(0)) * 1000;
    const int tile = int(state.range(1));
    SphereChunk s = sphere_setups(triangles);
    pipeline::ChunkBins& chunk = s.chunk;
    const TileGrid grid(1920, 1080, tile);
    std::vector<uint32_t> scratch;
    chunk.bin(s.items, s.setups, grid, scratch);
    pipeline::TileBuffers buffers;
    for (auto _ : state) {
        for (int t = 0; t < grid.count(); ++t) {
            const int tx = t % grid.tiles_x, ty = t / grid.tiles_x;
            const TileRect rect{tx * tile, ty * tile, std::min((tx + 1) * tile, 1920), std::min((ty + 1) * tile, 1080)};
            buffers.clear(tile);
            for (const pipeline::TriangleSetup* e = chunk.stored(t); e != chunk.stored(t) + (chunk.end(t) - chunk.begin(t)); ++e)
                pipeline::rasterize_opaque(*e, rect, buffers);
            benchmark::DoNotOptimize(buffers.depth.data());
        }
    }
    state.counters["tri/s"] =
        benchmark::Counter(double(s.setups.size()), benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_TileRaster)
    ->ArgNames({"ktris", "tile"})
    ->ArgsProduct({{100, 1000}, {32, 64, 128}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
