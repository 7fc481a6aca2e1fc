// Whole animation frames of the shipped scenes through FrameRenderer, the work `tessera
// render` does per frame (animate, bake, BVH, visibility, shading, shadows, passes), without
// the PNG encoding. Arguments: renderer (0 raster, 1 raytrace) and shadows (0 none, 1 map,
// 2 rays), so the three shadow methods and the two renderers compare on identical frames.
// Each iteration renders the next frame of the animation (time advances 1/24 s).
#include <benchmark/benchmark.h>

#include <filesystem>
#include <map>
#include <memory>
#include <string>

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

}  // namespace
