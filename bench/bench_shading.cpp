// Shading benchmarks: cost per shaded pixel for each model (SIMD kernel, one thread, pixels
// of a 1080p visibility buffer), the scalar reference kernel for the SIMD speed-up, texture
// sampling throughput per filter (scalar and gathering SIMD), and whole 1080p Phong frames of a 1M-triangle scene through
// the tile rasterizer + shading (the comparison with llvmpipe running a Phong GLSL
// shader; see BENCHMARKS.md).
//
// Counters: pix/s and samples/s are rates.
#include <benchmark/benchmark.h>

#include <tbb/global_control.h>

#include <memory>
#include <random>

#include "raster/geometry/param_surface.h"
#include "raster/geometry/surfaces.h"
#include "raster/pipeline/rasterizer.h"
#include "raster/render/frame_renderer.h"
#include "raster/scene_file/scene_build.h"
#include "raster/shade/frame_shading.h"
#include "raster/texture/sampler.h"
#include "raster/texture/sampler_simd.h"

namespace {

using namespace tessera;

constexpr int kWidth = 1920, kHeight = 1080;

texture::Texture checker(int size) {
    std::vector<glm::vec4> t(size_t(size) * size_t(size));
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x)
            t[size_t(y * size + x)] = ((x / 8 + y / 8) & 1) ? glm::vec4(0.9f, 0.8f, 0.6f, 1) : glm::vec4(0.2f, 0.3f, 0.5f, 1);
    return texture::Texture(size, size, std::move(t));
}

texture::Texture bumps(int size) {
    std::vector<glm::vec4> t(size_t(size) * size_t(size));
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            const float a = 6.2831853f * 8.0f * float(x) / float(size), b = 6.2831853f * 8.0f * float(y) / float(size);
            const glm::vec3 n = glm::normalize(glm::vec3(-0.3f * std::cos(a) * std::sin(b), -0.3f * std::sin(a) * std::cos(b), 1));
            t[size_t(y * size + x)] = glm::vec4(n * 0.5f + 0.5f, 1.0f);
        }
    return texture::Texture(size, size, std::move(t));
}

// A sphere of `n` x `n/2` quads filling most of a 1080p view, two lights, one material whose
// model and textures the benchmark picks.
scene::Scene sphere_scene(int n) {
    scene::Scene s;
    s.camera.eye = {0, 0, 2.6f};
    s.camera.aspect = float(kWidth) / float(kHeight);
    s.lights = {scene::point_light({2, 2, 3}, glm::vec3(0.1f), glm::vec3(0.9f)),
                scene::directional_light({-1, 0.5f, 1}, glm::vec3(0.05f), glm::vec3(0.3f))};
    s.textures.push_back(checker(512));
    s.textures.push_back(bumps(512));
    s.materials.push_back(scene::Material{});
    s.objects.push_back(scene::Object{"sphere", std::make_shared<const Mesh>(geometry::tessellate(geometry::sphere_surface({0, 0, 0}, 1.0f), n, n / 2)),
                               0, {}, {}});
    return s;
}

struct Fixture {
    scene::Scene scene = sphere_scene(256);
    scene::BakedScene baked = scene::bake(scene);
    std::vector<shade::CoveredPixel> pixels;
    Fixture() {
        pipeline::Rasterizer r;
        VisibilityBuffer vis;
        r.render(baked.mesh, scene.camera.view_projection(), pipeline::Viewport(kWidth, kHeight), pipeline::RasterOptions{}, vis);
        for (int y = 0; y < kHeight; ++y)
            for (int x = 0; x < kWidth; ++x)
                if (const uint32_t t = vis.triangle[size_t(y) * kWidth + size_t(x)]; t != kNoTriangle)
                    pixels.push_back({x, y, t});
    }
};

Fixture& fixture() {
    static Fixture f;
    return f;
}

// Mode: 0 flat, 1 gouraud, 2 phong, 3 toon, 4 phong + diffuse texture, 5 phong + normal map.
void configure(scene::Material& m, int mode) {
    m = scene::Material{};
    m.model = mode == 0 ? scene::ShadingModel::flat : mode == 1 ? scene::ShadingModel::gouraud : mode == 3 ? scene::ShadingModel::toon
                                                                                             : scene::ShadingModel::phong;
    if (mode == 4) m.diffuse_texture = 0;
    if (mode == 5) m.normal_texture = 1;
}

const char* mode_name(int mode) {
    static const char* names[] = {"flat", "gouraud", "phong", "toon", "phong_textured", "phong_normalmap"};
    return names[mode];
}

void BM_ShadePixels(benchmark::State& state) {
    const int mode = int(state.range(0));
    const bool reference = state.range(1) != 0;
    Fixture& f = fixture();
    configure(f.scene.materials[0], mode);
    tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
    const shade::FrameShading shading(f.baked, f.scene, shade::RenderState{f.scene.camera, kWidth, kHeight, f.scene.lights});
    std::vector<glm::vec4> out(f.pixels.size());
    for (auto _ : state) {
        if (reference) shading.shade_reference(f.pixels, out);
        else shading.shade(f.pixels, out);
        benchmark::DoNotOptimize(out.data());
    }
    state.SetLabel(std::string(mode_name(mode)) + (reference ? " scalar" : " simd"));
    state.counters["pix/s"] = benchmark::Counter(double(f.pixels.size()) * double(state.iterations()),
                                                 benchmark::Counter::kIsRate);
    state.counters["pixels"] = double(f.pixels.size());
}
BENCHMARK(BM_ShadePixels)
    ->ArgsProduct({{0, 1, 2, 3, 4, 5}, {0}})
    ->Args({2, 1})
    ->Args({5, 1})
    ->Unit(benchmark::kMillisecond);

// A sampler benchmark's label (its filter, the first argument) and its rate of samples.
void label_sampler(benchmark::State& state, size_t samples_per_iteration) {
    static const char* names[] = {"nearest", "bilinear", "mipmap", "trilinear"};
    state.SetLabel(names[state.range(0)]);
    state.counters["samples/s"] = benchmark::Counter(double(samples_per_iteration) * double(state.iterations()),
                                                     benchmark::Counter::kIsRate);
}

void BM_TextureSample(benchmark::State& state) {
    const auto filter = texture::TextureFilter(state.range(0));
    static const texture::Texture texture = checker(1024);
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> uv(-2.0f, 2.0f), scale(0.1f, 8.0f);
    struct Query {
        glm::vec2 uv;
        texture::UvDerivatives d;
    };
    std::vector<Query> queries(1 << 16);
    for (Query& q : queries) {
        const float s = scale(rng) / 1024.0f;
        q = {{uv(rng), uv(rng)}, {{s, 0.0f}, {0.0f, s * 0.7f}}};
    }
    glm::vec4 sum(0.0f);
    for (auto _ : state) {
        for (const Query& q : queries) sum += texture::sample(texture, q.uv, q.d, filter, texture::TextureWrap::repeat);
        benchmark::DoNotOptimize(sum);
    }
    label_sampler(state, queries.size());
}
BENCHMARK(BM_TextureSample)->DenseRange(0, 3)->Unit(benchmark::kMicrosecond);

// The same queries kLanes at a time through the gathering sampler (sampler_simd.h).
void BM_TextureSampleSimd(benchmark::State& state) {
    const auto filter = texture::TextureFilter(state.range(0));
    static const texture::Texture texture = checker(1024);
    constexpr int L = simd::kLanes;
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> uv(-2.0f, 2.0f), scale(0.1f, 8.0f);
    struct alignas(64) Block {
        float u[L], v[L], d[L];
    };
    std::vector<Block> blocks((1 << 16) / L);
    for (Block& b : blocks)
        for (int i = 0; i < L; ++i) {
            b.u[i] = uv(rng);
            b.v[i] = uv(rng);
            b.d[i] = scale(rng) / 1024.0f;
        }
    using simd::vfloat;
    vfloat sum(0.0f);
    for (auto _ : state) {
        for (const Block& b : blocks) {
            const vfloat d = vfloat::load(b.d);
            const texture::TexelLanes t = texture::sample_lanes(texture, vfloat::load(b.u), vfloat::load(b.v), d,
                                                            vfloat(0.0f), vfloat(0.0f), d * vfloat(0.7f), filter,
                                                            texture::TextureWrap::repeat);
            sum = sum + t.r;
        }
        benchmark::DoNotOptimize(sum);
    }
    label_sampler(state, blocks.size() * L);
}
BENCHMARK(BM_TextureSampleSimd)->DenseRange(0, 3)->Unit(benchmark::kMicrosecond);

// As a frame samples a skin: a 256^2 texture (its chain in L2) read by 4x4 pixel stamps that
// walk across it, one texel per pixel step (level 0 and 1 under trilinear): the fetches hit
// the caches, so the sampler's own instructions are measured, gathers first.
void BM_TextureSampleSimdCoherent(benchmark::State& state) {
    const auto filter = texture::TextureFilter(state.range(0));
    static const texture::Texture texture = checker(256);
    constexpr int L = simd::kLanes;
    constexpr float kTexel = 1.0f / 256.0f;
    struct alignas(64) Block {
        float u[L], v[L];
    };
    std::vector<Block> blocks((1 << 16) / L);
    for (size_t k = 0; k < blocks.size(); ++k) {
        const float u0 = float(k % 64) * 4.0f * kTexel, v0 = float(k / 64 % 64) * 4.0f * kTexel;
        for (int i = 0; i < L; ++i) {
            blocks[k].u[i] = u0 + float(i % simd::kStampW) * kTexel * 1.1f;
            blocks[k].v[i] = v0 + float(i / simd::kStampW) * kTexel * 1.1f;
        }
    }
    using simd::vfloat;
    const vfloat d(1.1f * kTexel);
    vfloat sum(0.0f);
    for (auto _ : state) {
        for (const Block& b : blocks) {
            const texture::TexelLanes t = texture::sample_lanes(texture, vfloat::load(b.u), vfloat::load(b.v), d,
                                                            vfloat(0.0f), vfloat(0.0f), d, filter,
                                                            texture::TextureWrap::repeat);
            sum = sum + t.r + t.g + t.b + t.a;
        }
        benchmark::DoNotOptimize(sum);
    }
    label_sampler(state, blocks.size() * L);
}
BENCHMARK(BM_TextureSampleSimdCoherent)->DenseRange(0, 3)->Unit(benchmark::kMicrosecond);

// A whole 1080p frame through FrameRenderer (the `tessera render` path, no shadows): bake +
// raster + Phong shading of a 1M-triangle sphere (1000 x 500 quads).
void BM_PhongFrame1080p(benchmark::State& state) {
    const int threads = int(state.range(0));
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(threads));
    static render::AnimatedScene scene = render::still_scene(sphere_scene(1000));
    render::FrameRenderer renderer(scene, kWidth, kHeight, render::RendererKind::raster, render::ShadowMode::none);
    render::FrameStats stats;
    for (auto _ : state) {
        const Frame f = renderer.render(0.0f, &stats);
        benchmark::DoNotOptimize(f.pixels.data());
    }
    state.counters["triangles"] = double(stats.raster.triangles);
    state.counters["pixels"] = double(stats.raster.visible_pixels);
    // The last frame's split: the rasterizer's stages, and the tile passes (shading).
    state.counters["raster_ms"] = stats.raster.vertex_ms + stats.raster.setup_bin_ms + stats.raster.raster_ms;
    state.counters["shade_ms"] = stats.raster.passes_ms;
}
BENCHMARK(BM_PhongFrame1080p)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
