// Procedural generators: reaction-diffusion cell-steps per second (library step at 1 and 2
// threads vs the plain scalar step of procedural/reaction_diffusion_reference.h), a copy-bandwidth run that gives the RD
// memory roofline, noise samples per second, the terrain reliefs (batch and single point), and
// heightfield generation.
//
// RD roofline: a cell-step reads A and B (8 bytes) and writes A' and B' (8 bytes); the copy
// benchmark counts bytes the same way (STREAM convention: read + written, write-allocate
// traffic hidden in both), so roofline cells/s = copy bytes/s / 16.
//
// Threaded runs measure wall time (UseRealTime) and the process's CPU time
// (MeasureProcessCPUTime): on a shared machine, items / CPU seconds is the per-core rate while
// our threads actually ran, and the wall-time rate is what the run got.
#include <benchmark/benchmark.h>
#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include <cstring>
#include <vector>

#include "procedural/reaction_diffusion_reference.h"
#include "procedural/dunes.h"
#include "procedural/field.h"
#include "procedural/fractal_batch.h"
#include "procedural/hash.h"
#include "procedural/heightfield.h"
#include "procedural/noise.h"
#include "procedural/rd_initial.h"
#include "procedural/rd_presets.h"
#include "procedural/reaction_diffusion.h"

namespace tp = tessera::procedural;

namespace {

tp::GrayScott spots() {
    tp::GrayScott g;
    g.feed = tp::find_rd_preset("spots")->feed;
    g.kill = tp::find_rd_preset("spots")->kill;
    return g;
}

// A seeded state (noise patches). The step's speed does not depend on the values (no
// branches; denormals are flushed), which BM_RdStepDecayed checks.
tp::RdState patterned(int n) { return tp::rd_initial_noise(n, n, 1, 8.0f); }

// Args: grid side, threads, steps per call (1: one pass over the grid per step; 8: two
// temporally blocked passes of 4 fused steps, the path a long run takes).
void BM_RdStep(benchmark::State& state) {
    const int n = int(state.range(0));
    const int steps = int(state.range(2));
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(state.range(1)));
    tp::ReactionDiffusion rd(spots(), patterned(n));
    for (auto _ : state) rd.step(steps);
    state.SetItemsProcessed(state.iterations() * int64_t(n) * n * steps);
    state.counters["threads"] = double(state.range(1));
}

// The plain scalar step (one thread, modulo indexing): the baseline.
void BM_RdStepScalarBaseline(benchmark::State& state) {
    const int n = int(state.range(0));
    const tp::GrayScott g = spots();
    tp::RdState a = patterned(n), b = a;
    for (auto _ : state) {
        tp::reference::gray_scott_step(g, a, b);
        std::swap(a, b);
    }
    state.SetItemsProcessed(state.iterations() * int64_t(n) * n);
}

// A fully decayed grid (B = 1e-30 everywhere, falling through the denormal range): the library
// step flushes denormals (denormals.h), so this should run as fast as BM_RdStep.
void BM_RdStepDecayed(benchmark::State& state) {
    const int n = int(state.range(0));
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
    tp::ReactionDiffusion rd(spots(), tp::RdState{tp::Grid(n, n, 1.0f), tp::Grid(n, n, 1e-30f)});
    rd.step(200);  // B ~ 1e-39: denormal without FTZ
    for (auto _ : state) rd.step(8);
    state.SetItemsProcessed(state.iterations() * int64_t(n) * n * 8);
}

// The scalar baseline on the same decayed grid, without FTZ: shows what denormals cost.
void BM_RdStepScalarBaselineDecayed(benchmark::State& state) {
    const int n = int(state.range(0));
    const tp::GrayScott g = spots();
    tp::RdState a{tp::Grid(n, n, 1.0f), tp::Grid(n, n, 1e-38f)}, b = a;
    for (auto _ : state) {
        tp::reference::gray_scott_step(g, a, b);
        std::swap(a, b);
        // Keep B inside the denormal range instead of letting it decay to zero.
        if (b.b.values[0] == 0.0f) std::fill(a.b.values.begin(), a.b.values.end(), 1e-39f);
    }
    state.SetItemsProcessed(state.iterations() * int64_t(n) * n);
}

// Copy bandwidth over a buffer far larger than the caches (2 x 256 MiB), at 1 or 2 threads.
void BM_CopyBandwidth(benchmark::State& state) {
    const size_t floats = size_t(64) << 20;
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(state.range(0)));
    std::vector<float> src(floats, 1.0f), dst(floats, 0.0f);
    for (auto _ : state) {
        tbb::parallel_for(tbb::blocked_range<size_t>(0, floats, size_t(1) << 18),
                          [&](const tbb::blocked_range<size_t>& r) {
                              std::memcpy(dst.data() + r.begin(), src.data() + r.begin(),
                                          r.size() * sizeof(float));
                          });
        benchmark::ClobberMemory();
    }
    state.SetBytesProcessed(state.iterations() * int64_t(floats) * 8);  // read + written
    state.counters["threads"] = double(state.range(0));
}

std::vector<float> random_coords(size_t n, float range, uint64_t seed) {
    tp::SplitMix64 rng(seed);
    std::vector<float> v(n);
    for (float& x : v) x = rng.next_float() * range;
    return v;
}

// 3-D value noise with its analytic gradient, one thread, 4096-point batches.
void BM_ValueNoise3Gradient(benchmark::State& state) {
    const size_t n = 4096;
    const auto x = random_coords(n, 64, 1), y = random_coords(n, 64, 2), z = random_coords(n, 64, 3);
    std::vector<float> v(n), gx(n), gy(n), gz(n);
    for (auto _ : state) {
        tp::value_noise_batch(7, n, x.data(), y.data(), z.data(), v.data(), gx.data(), gy.data(), gz.data());
        benchmark::DoNotOptimize(v.data());
    }
    state.SetItemsProcessed(state.iterations() * int64_t(n));
}

// The same over 1M points split into 4096-point batches across 1 or 2 threads.
void BM_ValueNoise3GradientThreads(benchmark::State& state) {
    const size_t n = size_t(1) << 20, batch = 4096;
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(state.range(0)));
    const auto x = random_coords(n, 64, 1), y = random_coords(n, 64, 2), z = random_coords(n, 64, 3);
    std::vector<float> v(n), gx(n), gy(n), gz(n);
    for (auto _ : state) {
        tbb::parallel_for(tbb::blocked_range<size_t>(0, n / batch, 1), [&](const tbb::blocked_range<size_t>& r) {
            for (size_t b = r.begin(); b < r.end(); ++b) {
                const size_t o = b * batch;
                tp::value_noise_batch(7, batch, x.data() + o, y.data() + o, z.data() + o, v.data() + o,
                                      gx.data() + o, gy.data() + o, gz.data() + o);
            }
        });
        benchmark::DoNotOptimize(v.data());
    }
    state.SetItemsProcessed(state.iterations() * int64_t(n));
    state.counters["threads"] = double(state.range(0));
}

void BM_GradientNoise3Gradient(benchmark::State& state) {
    const size_t n = 4096;
    const auto x = random_coords(n, 64, 1), y = random_coords(n, 64, 2), z = random_coords(n, 64, 3);
    std::vector<float> v(n), gx(n), gy(n), gz(n);
    for (auto _ : state) {
        tp::gradient_noise_batch(7, n, x.data(), y.data(), z.data(), v.data(), gx.data(), gy.data(), gz.data());
        benchmark::DoNotOptimize(v.data());
    }
    state.SetItemsProcessed(state.iterations() * int64_t(n));
}

// 2-D value-noise fBm with gradient over a 512 x 512 grid, one thread; items = octave-samples.
void BM_Fbm2OctaveSamples(benchmark::State& state) {
    const int n = 512, octaves = 8;
    const tp::Fractal f{octaves, 2.0f, 0.5f, 3};
    std::vector<float> xs(n), ys(n), v(n), dx(n), dy(n);
    for (int i = 0; i < n; ++i) xs[i] = float(i) / 64.0f;
    for (auto _ : state) {
        for (int row = 0; row < n; ++row) {
            std::fill(ys.begin(), ys.end(), float(row) / 64.0f);
            tp::fbm_batch(f, tp::OpenLattice{}, n, xs.data(), ys.data(), v.data(), dx.data(), dy.data());
            benchmark::DoNotOptimize(v.data());
        }
    }
    state.SetItemsProcessed(state.iterations() * int64_t(n) * n * octaves);
}

// The implicit fields a ray marcher calls, value + gradient per sample, one thread.
template <class Field>
void field_samples(benchmark::State& state, const Field& field, float range) {
    const size_t n = 4096;
    const auto x = random_coords(n, range, 1), y = random_coords(n, 1.0f, 2), z = random_coords(n, range, 3);
    std::vector<float> v(n), gx(n), gy(n), gz(n);
    for (auto _ : state) {
        field.sample_batch(n, x.data(), y.data(), z.data(), v.data(), gx.data(), gy.data(), gz.data());
        benchmark::DoNotOptimize(v.data());
    }
    state.SetItemsProcessed(state.iterations() * int64_t(n));
}
void BM_SineNoiseFieldSamples(benchmark::State& state) { field_samples(state, tp::SineNoiseField(), 10.0f); }
void BM_TerrainFieldSamples(benchmark::State& state) {
    tp::TerrainParams p;
    p.fractal.octaves = 6;
    field_samples(state, tp::TerrainField(p), 1000.0f);
}

// The terrain reliefs over 4096 points, one thread: args {relief (0 fbm, 1 ridged, 2 warped,
// 3 dunes), gradient?, batch?}. Batch is the vectorised form (fractal_batch.h, dunes.h), the
// other the single-point reference in a loop; without gradient the batch computes values only
// (what a marcher's steps need). items = points; octave_samples = points x 2-D noise octaves
// evaluated per point (5 for fbm and ridged, 15 for warped's three fBm, 5 for the dunes' two).
void BM_Relief(benchmark::State& state) {
    const int relief = int(state.range(0));
    const bool gradient = state.range(1) != 0, batch = state.range(2) != 0;
    const size_t n = 4096;
    const auto x = random_coords(n, 200, 1), y = random_coords(n, 200, 2);
    std::vector<float> v(n), gx(n), gy(n);
    const tp::Fractal f{5, 2.0f, 0.5f, 3};
    const tp::Dunes d;
    const tp::DuneWaves<tp::OpenLattice> waves = tp::dune_waves(d);
    const tp::OpenLattice open;
    float* dx = gradient ? gx.data() : nullptr;
    float* dy = gradient ? gy.data() : nullptr;
    auto single = [&](glm::vec2 p) {
        switch (relief) {
            case 0: return tp::fbm(p, f, open);
            case 1: return tp::ridged(p, f, open);
            case 2: return tp::domain_warp(p, f, 0.7f, open);
            default: return tp::dunes(p, d, waves);
        }
    };
    for (auto _ : state) {
        if (!batch) {
            for (size_t i = 0; i < n; ++i) {
                const tp::Noise2 s = single({x[i], y[i]});
                v[i] = s.value;
                if (gradient) gx[i] = s.gradient.x, gy[i] = s.gradient.y;
            }
        } else {
            switch (relief) {
                case 0: tp::fbm_batch(f, open, n, x.data(), y.data(), v.data(), dx, dy); break;
                case 1: tp::ridged_batch(f, 1.0f, open, n, x.data(), y.data(), v.data(), dx, dy); break;
                case 2: tp::domain_warp_batch(f, 0.7f, open, n, x.data(), y.data(), v.data(), dx, dy); break;
                default: tp::dunes_batch(d, waves, n, x.data(), y.data(), v.data(), dx, dy); break;
            }
        }
        benchmark::DoNotOptimize(v.data());
        benchmark::DoNotOptimize(gx.data());
    }
    state.SetItemsProcessed(state.iterations() * int64_t(n));
    const int octaves[] = {5, 5, 15, 5};
    state.counters["octave_samples"] =
        benchmark::Counter(double(state.iterations()) * double(n) * octaves[relief], benchmark::Counter::kIsRate);
}

// Whole tileable heightfield (8 octaves), args: side, threads.
void BM_Heightfield(benchmark::State& state) {
    const int n = int(state.range(0));
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(state.range(1)));
    tp::HeightfieldParams p;
    for (auto _ : state) benchmark::DoNotOptimize(tp::generate_heightfield(n, n, p).values.data());
    state.SetItemsProcessed(state.iterations() * int64_t(n) * n * p.fractal.octaves);
    state.counters["threads"] = double(state.range(1));
}

}  // namespace

BENCHMARK(BM_RdStep)->ArgsProduct({{256, 512, 1024, 2048}, {1, 2}, {1, 8}})->MeasureProcessCPUTime()->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_RdStep)->ArgsProduct({{4096, 8192}, {1, 2}, {1, 8}})->Iterations(2)->MeasureProcessCPUTime()->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_RdStepScalarBaseline)->Arg(256)->Arg(512)->Arg(1024)->Arg(2048)->MeasureProcessCPUTime()->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_RdStepScalarBaseline)->Arg(4096)->Arg(8192)->Iterations(1)->MeasureProcessCPUTime()->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_RdStepDecayed)->Arg(1024)->MeasureProcessCPUTime()->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_RdStepScalarBaselineDecayed)->Arg(1024)->MeasureProcessCPUTime()->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_CopyBandwidth)->Arg(1)->Arg(2)->MeasureProcessCPUTime()->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ValueNoise3Gradient)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_ValueNoise3GradientThreads)->Arg(1)->Arg(2)->MeasureProcessCPUTime()->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_GradientNoise3Gradient)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Fbm2OctaveSamples)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_SineNoiseFieldSamples)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_TerrainFieldSamples)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Relief)
    ->ArgNames({"relief", "gradient", "batch"})
    ->ArgsProduct({{0, 1, 2, 3}, {0, 1}, {0, 1}})
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Heightfield)->ArgsProduct({{2048}, {1, 2}})->MeasureProcessCPUTime()->UseRealTime()->Unit(benchmark::kMillisecond);
