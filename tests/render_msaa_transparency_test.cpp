// Transparent triangles under MSAA (render/layer_split.h): a blended or alpha-tested
// triangle whose edge crosses pixels of one opaque surface gives each such pixel exactly
// (k / n) of the covered colour and (n - k) / n of the uncovered one in linear light, k the
// samples it covers (computed here from the geometry, independently of the renderers), in
// both renderers; pixels it covers wholly or not at all keep their one-sample colour to the
// bit; and the frame is the same for any thread count, shadows included.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>
#include <cstring>
#include <memory>

#include "raster/pipeline/sample_pattern.h"
#include "raster/render/frame_renderer.h"
#include "shading_scenes.h"

using namespace tessera;

namespace {

constexpr int kWidth = 96, kHeight = 64;
constexpr float kEyeZ = 4.0f, kFovy = 40.0f, kFront = -0.25f;
// The front triangle: its edge A-B crosses the frame diagonally, the others lie outside it.
const glm::vec2 kA{-1.6f, -3.0f}, kB{1.2f, 3.0f}, kC{-8.0f, 0.0f};

using test::flat_colour;

// A red square filling the view at z = -0.5, and in front of it the green triangle, blended
// (opacity 0.5) or alpha-tested (cutoff 0.5, alpha 1: it survives everywhere).
render::AnimatedScene edge_scene(bool masked) {
    scene::Scene s;
    s.camera.eye = {0, 0, kEyeZ};
    s.camera.fovy_deg = kFovy;
    s.camera.near = 1.0f;
    s.camera.far = 10.0f;
    s.lights = {scene::directional_light({0, 0, 1}, glm::vec3(0.25f), glm::vec3(0.75f))};
    s.background.colour = glm::vec3(0.0f);
    scene::Material green = flat_colour({0, 1, 0});
    if (masked) green.alpha_cutoff = 0.5f;
    else green.opacity = 0.5f;
    s.materials = {flat_colour({1, 0, 0}), green};
    auto back = std::make_shared<Mesh>();
    back->positions = {{-4, -4, -0.5f}, {4, -4, -0.5f}, {4, 4, -0.5f}, {-4, 4, -0.5f}};
    back->normals.assign(4, glm::vec3(0, 0, 1));
    back->indices = {0, 1, 2, 0, 2, 3};
    auto front = std::make_shared<Mesh>();
    front->positions = {{kA, kFront}, {kB, kFront}, {kC, kFront}};
    front->normals.assign(3, glm::vec3(0, 0, 1));
    front->indices = {0, 1, 2};
    s.objects = {{"back", back, 0, {}, {}}, {"front", front, 1, {}, {}}};
    return render::still_scene(std::move(s));
}

Frame render(bool masked, render::RendererKind kind, int samples, int threads = 0,
             render::ShadowMode shadows = render::ShadowMode::none) {
    std::unique_ptr<tbb::global_control> limit;
    if (threads > 0) limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, threads);
    render::AnimatedScene scene = edge_scene(masked);
    render::FrameRenderer frames(scene, kWidth, kHeight, kind, shadows, samples);
    return frames.render(0.0f);
}

// A point of the front plane in window coordinates (pixels, rows down), in double.
glm::dvec2 window(glm::vec2 p) {
    const double half_h = (kEyeZ - kFront) * std::tan(double(kFovy) * 0.5 * M_PI / 180.0);
    const double half_w = half_h * double(kWidth) / double(kHeight);
    return {(double(p.x) / half_w + 1.0) * 0.5 * kWidth, (1.0 - double(p.y) / half_h) * 0.5 * kHeight};
}

// The samples of pixel (x, y) inside the front triangle, or -1 where a sample lies within
// 1/64 pixel of the edge A-B (vertex snapping moves it by up to 1/512).
int covered_samples(int x, int y, int samples) {
    const glm::dvec2 a = window(kA), b = window(kB), c = window(kC);
    const glm::dvec2 edge = b - a;
    const double length = std::sqrt(edge.x * edge.x + edge.y * edge.y);
    const auto side = [&](glm::dvec2 p) { return (edge.x * (p.y - a.y) - edge.y * (p.x - a.x)) / length; };
    const double inside = side(c) > 0 ? 1.0 : -1.0;
    int k = 0;
    for (const pipeline::SampleOffset& o : pipeline::sample_pattern(samples)) {
        const glm::dvec2 p(x + 0.5 + o.x / 16.0, y + 0.5 + o.y / 16.0);
        const double d = side(p) * inside;
        if (std::abs(d) < 1.0 / 64.0) return -1;
        k += d > 0;
    }
    return k;
}

TEST(RenderMsaaTransparency, EdgePixelsMixByCoveredSamples) {
    for (const bool masked : {false, true})
        for (const auto kind : {render::RendererKind::raster, render::RendererKind::raytrace})
            for (const int samples : {4, 8}) {
                const Frame one = render(masked, kind, 1);
                const Frame multi = render(masked, kind, samples);
                // The colours the edge mixes: red alone, and red under green (blended or in
                // its place), from pixels wholly on either side.
                glm::vec4 uncovered(-1.0f), covered(-1.0f);
                size_t partial = 0, whole = 0;
                for (int y = 0; y < kHeight; ++y)
                    for (int x = 0; x < kWidth; ++x) {
                        const int k = covered_samples(x, y, samples);
                        if (k == 0) uncovered = one.at(x, y);
                        if (k == samples) covered = one.at(x, y);
                    }
                ASSERT_NEAR(uncovered.r, 1.0f, 1e-5f);
                ASSERT_NEAR(covered.g, masked ? 1.0f : 0.5f, 1e-5f);
                for (int y = 0; y < kHeight; ++y)
                    for (int x = 0; x < kWidth; ++x) {
                        const int k = covered_samples(x, y, samples);
                        if (k < 0) continue;
                        const glm::vec4 got = multi.at(x, y);
                        if (k == 0 || k == samples) {
                            // Wholly on one side: the one-sample colour, to the bit.
                            ASSERT_EQ(0, std::memcmp(&got, &one.at(x, y), sizeof(got)))
                                << masked << " " << int(kind) << " " << samples << " at " << x << "," << y;
                            ++whole;
                            continue;
                        }
                        const float share = float(k) / float(samples);
                        const glm::vec4 expected = covered * share + uncovered * (1.0f - share);
                        for (int c = 0; c < 4; ++c)
                            ASSERT_NEAR(got[c], expected[c], 1e-5f) << "masked " << masked << " renderer " << int(kind)
                                                                    << " samples " << samples << " pixel " << x << ","
                                                                    << y << " k " << k << " channel " << c;
                        ++partial;
                    }
                EXPECT_GT(partial, 30u);  // about one per row along the edge
                EXPECT_GT(whole, size_t(kWidth * kHeight) / 2);
            }
}

TEST(RenderMsaaTransparency, SameForAnyThreadCount) {
    for (const bool masked : {false, true})
        for (const auto kind : {render::RendererKind::raster, render::RendererKind::raytrace}) {
            // With shadow rays: the split pixels' groups run the shadow pass too.
            const Frame a = render(masked, kind, 4, 1, render::ShadowMode::rays);
            const Frame b = render(masked, kind, 4, 2, render::ShadowMode::rays);
            EXPECT_EQ(0, std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(glm::vec4)))
                << masked << " " << int(kind);
        }
}

}  // namespace
