// Whole animation frames of the shipped scenes through FrameRenderer, the work `tessera
// render` does per frame (animate, bake, BVH, visibility, shading, shadows, passes), without
// the PNG encoding. Arguments: renderer (0 raster, 1 raytrace) and shadows (0 none, 1 map,
// 2 rays), so the three shadow methods and the two renderers compare on identical frames.
// Each iteration renders the next frame of the animation (time advances 1/24 s).
//
// Then the PNG path of a frame, stage by stage on one thread (BM_Png*): a 1920x1080 float
// frame made here (see png_frame) through encode_srgb8, the Paeth filter, Adler-32 and the
// run-length deflate of each 64-row band, and the whole PngEncoder::encode; each reports the
// bytes it reads per second (bytes_per_second), to hold against the machine's copy bandwidth.
#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include <glm/vec4.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "raster/output/adler32.h"
#include "raster/output/png_encoder.h"
#include "raster/output/png_paeth.h"
#include "raster/output/rle_deflate.h"
#include "raster/output/srgb8.h"
#include "raster/render/frame_renderer.h"
#include "raster/scene_file/scene_build.h"
#include "raster/scene_file/scene_parse.h"

namespace {

using namespace tessera;

const std::filesystem::path kScenes = TESSERA_SCENE_DIR;

// Built once per scene: reaction-diffusion skins take a second or two to grow.
render::AnimatedScene& scene(const std::string& name) {
    static std::map<std::string, std::unique_ptr<render::AnimatedScene>> cache;
    auto& slot = cache[name];
    if (!slot) {
        std::vector<std::string> warnings;
        slot = std::make_unique<render::AnimatedScene>(scene_file::build_scene(scene_file::load_scene_file(kScenes / (name + ".json"), warnings)));
    }
    return *slot;
}

void frames(benchmark::State& state, const std::string& name, int width, int height) {
    const auto renderer = state.range(0) == 0 ? render::RendererKind::raster : render::RendererKind::raytrace;
    const render::ShadowMode shadows[] = {render::ShadowMode::none, render::ShadowMode::map, render::ShadowMode::rays};
    render::FrameRenderer r(scene(name), width, height, renderer, shadows[state.range(1)]);
    int frame = 0;
    render::FrameStats stats;
    for (auto _ : state) {
        Frame f = r.render(float(frame++) / 24.0f, &stats);
        benchmark::DoNotOptimize(f.pixels.data());
    }
    state.counters["triangles"] = double(stats.triangles);
    state.counters["fps"] = benchmark::Counter(double(state.iterations()), benchmark::Counter::kIsRate);
}

void BM_Snakes720p(benchmark::State& state) { frames(state, "snakes", 1280, 720); }
BENCHMARK(BM_Snakes720p)->ArgsProduct({{0, 1}, {0, 1, 2}})->ArgNames({"raytrace", "shadows"})
    ->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_Stress1080p(benchmark::State& state) { frames(state, "stress", 1920, 1080); }
BENCHMARK(BM_Stress1080p)->ArgsProduct({{0, 1}, {0}})->ArgNames({"raytrace", "shadows"})
    ->Unit(benchmark::kMillisecond)->UseRealTime();

// --- The PNG path -------------------------------------------------------------------------

constexpr int kPngWidth = 1920, kPngHeight = 1080;

// A linear RGBA frame with what rendered frames have: a smooth sky gradient (top third),
// flat-coloured regions (blocks of a few colours, like unlit walls and the background), and
// shaded surfaces, gradients with a little noise as from textures and sampling. Seeded, so
// every run codes the same bytes.
const std::vector<glm::vec4>& png_frame() {
    static const std::vector<glm::vec4> frame = [] {
        std::vector<glm::vec4> f(size_t(kPngWidth) * kPngHeight);
        std::mt19937 rng(21);
        std::normal_distribution<float> noise(0.0f, 0.01f);
        for (int y = 0; y < kPngHeight; ++y)
            for (int x = 0; x < kPngWidth; ++x) {
                const float u = float(x) / kPngWidth, v = float(y) / kPngHeight;
                glm::vec4 c;
                if (v < 1.0f / 3.0f) {
                    c = glm::vec4(0.2f + 0.3f * v, 0.35f + 0.4f * v, 0.8f - 0.2f * u, 1.0f);
                } else if (((x / 240) + (y / 180)) % 3 == 0) {
                    const float k = float((x / 240) % 4) * 0.15f;
                    c = glm::vec4(0.1f + k, 0.12f, 0.3f - 0.5f * k, 1.0f);
                } else {
                    const float shade = 0.5f + 0.4f * std::sin(6.0f * u + 3.0f * v);
                    c = glm::vec4(shade * 0.8f + noise(rng), shade * 0.6f + noise(rng), shade * 0.3f + noise(rng), 1.0f);
                }
                f[size_t(y) * kPngWidth + size_t(x)] = c;
            }
        return f;
    }();
    return frame;
}

// The frame as the PNG writer gets it: 8-bit, `channels` 3 (RGB) or 4 (RGBA) per pixel.
const std::vector<uint8_t>& png_bytes(int channels) {
    static std::map<int, std::vector<uint8_t>> cache;
    std::vector<uint8_t>& bytes = cache[channels];
    if (bytes.empty()) {
        const std::vector<glm::vec4>& f = png_frame();
        std::vector<uint8_t> rgba(f.size() * 4);
        output::encode_srgb8(f.data(), f.size(), rgba.data());
        bytes.resize(f.size() * size_t(channels));
        for (size_t p = 0; p < f.size(); ++p)
            std::copy_n(rgba.data() + 4 * p, channels, bytes.data() + p * size_t(channels));
    }
    return bytes;
}

// Its rows Paeth-filtered as the encoder stores them: a filter-type byte, then the residuals.
const std::vector<uint8_t>& png_filtered(int channels) {
    static std::map<int, std::vector<uint8_t>> cache;
    std::vector<uint8_t>& filtered = cache[channels];
    if (filtered.empty()) {
        const std::vector<uint8_t>& bytes = png_bytes(channels);
        const size_t n = size_t(kPngWidth) * size_t(channels);
        const std::vector<uint8_t> zeros(n, 0);
        filtered.resize(size_t(kPngHeight) * (n + 1));
        for (int y = 0; y < kPngHeight; ++y) {
            uint8_t* out = filtered.data() + size_t(y) * (n + 1);
            out[0] = 4;
            output::paeth_residuals_reference(bytes.data() + size_t(y) * n, y == 0 ? zeros.data() : bytes.data() + size_t(y - 1) * n,
                                              n, size_t(channels), out + 1);
        }
    }
    return filtered;
}

void BM_PngSrgb8(benchmark::State& state) {
    const std::vector<glm::vec4>& f = png_frame();
    std::vector<uint8_t> out(f.size() * 4);
    for (auto _ : state) {
        benchmark::DoNotOptimize(output::encode_srgb8(f.data(), f.size(), out.data()));
        benchmark::ClobberMemory();
    }
    state.SetBytesProcessed(int64_t(state.iterations()) * int64_t(f.size() * sizeof(glm::vec4)));
}
BENCHMARK(BM_PngSrgb8)->Unit(benchmark::kMillisecond);

// Argument 0: paeth_residuals_reference (the standard's predictor, byte by byte); 1: the fast
// form the encoder uses.
void BM_PngPaeth(benchmark::State& state) {
    const int channels = int(state.range(1));
    const std::vector<uint8_t>& bytes = png_bytes(channels);
    const size_t n = size_t(kPngWidth) * size_t(channels);
    const std::vector<uint8_t> zeros(n, 0);
    std::vector<uint8_t> out(bytes.size());
    const auto filter = state.range(0) == 0 ? output::paeth_residuals_reference : output::paeth_residuals;
    for (auto _ : state) {
        for (int y = 0; y < kPngHeight; ++y)
            filter(bytes.data() + size_t(y) * n, y == 0 ? zeros.data() : bytes.data() + size_t(y - 1) * n, n,
                   size_t(channels), out.data() + size_t(y) * n);
        benchmark::ClobberMemory();
    }
    state.SetBytesProcessed(int64_t(state.iterations()) * int64_t(bytes.size()));
}
BENCHMARK(BM_PngPaeth)->ArgsProduct({{0, 1}, {3, 4}})->ArgNames({"fast", "channels"})->Unit(benchmark::kMillisecond);

void BM_PngAdler32(benchmark::State& state) {
    const std::vector<uint8_t>& filtered = png_filtered(int(state.range(0)));
    for (auto _ : state) benchmark::DoNotOptimize(output::adler32_update(1, filtered.data(), filtered.size()));
    state.SetBytesProcessed(int64_t(state.iterations()) * int64_t(filtered.size()));
}
BENCHMARK(BM_PngAdler32)->ArgName("channels")->Arg(3)->Arg(4)->Unit(benchmark::kMillisecond);

// The filtered frame deflated band by band (kPngBandRows rows), as the encoder does.
void BM_PngRleDeflate(benchmark::State& state) {
    const std::vector<uint8_t>& filtered = png_filtered(int(state.range(0)));
    const size_t band = size_t(output::kPngBandRows) * (filtered.size() / kPngHeight);
    output::RleDeflate rle;
    size_t compressed = 0;
    for (auto _ : state) {
        compressed = 0;
        for (size_t start = 0; start < filtered.size(); start += band) {
            const size_t size = std::min(band, filtered.size() - start);
            compressed += rle.compress({filtered.data() + start, size}, start + size == filtered.size()).size();
        }
    }
    state.SetBytesProcessed(int64_t(state.iterations()) * int64_t(filtered.size()));
    state.counters["ratio"] = double(filtered.size()) / double(compressed);
}
BENCHMARK(BM_PngRleDeflate)->ArgName("channels")->Arg(3)->Arg(4)->Unit(benchmark::kMillisecond);

// The whole file from the 8-bit frame, on one thread.
void BM_PngEncode(benchmark::State& state) {
    const int channels = int(state.range(0));
    const std::vector<uint8_t>& bytes = png_bytes(channels);
    tbb::global_control one_thread(tbb::global_control::max_allowed_parallelism, 1);
    output::PngEncoder encoder;
    size_t file = 0;
    for (auto _ : state) file = encoder.encode(bytes.data(), kPngWidth, kPngHeight, channels).size();
    state.SetBytesProcessed(int64_t(state.iterations()) * int64_t(bytes.size()));
    state.counters["file_bytes"] = double(file);
}
BENCHMARK(BM_PngEncode)->ArgName("channels")->Arg(3)->Arg(4)->Unit(benchmark::kMillisecond);

}  // namespace
