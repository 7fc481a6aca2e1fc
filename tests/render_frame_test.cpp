// The frame renderer: shadow rays darken exactly what a light cannot reach; the raster and
// ray-cast renderers agree; the result is the same with 1 and 2 threads; the trace is valid
// JSON with named worker tracks and slices for frames, stages and tiles.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <tbb/global_control.h>

#include <filesystem>
#include <fstream>
#include <cstring>
#include <limits>
#include <set>
#include <string>

#include "raster/output/srgb8.h"
#include "raster/render/frame_renderer.h"
#include "raster/scene_file/scene_build.h"
#include "raster/scene_file/scene_parse.h"
#include "raster/core/trace.h"
#include "raster/workloads/test_meshes.h"

namespace fs = std::filesystem;
using namespace tessera;

namespace {

// A ball hovering over a floor, lit straight from above by a distant light.
const char* kBallOverFloor = R"({
  "camera": {"eye": [0, 3, 4], "lookat": [0, 0, 0], "fov": 50},
  "background": {"type": "colour", "colour": [0.2, 0.3, 0.4]},
  "lights": [{"direction": [0, 1, 0], "La": [0.2, 0.2, 0.2], "Le": [1, 1, 1]}],
  "materials": {"grey": {"model": "phong", "kd": [0.6, 0.6, 0.6], "ka": [0.5, 0.5, 0.5], "ks": [0, 0, 0]},
                "red": {"model": "phong", "kd": [0.8, 0.1, 0.1]}},
  "objects": [
    {"type": "box", "material": "grey", "size": [6, 0.2, 6], "transform": {"translate": [0, -1.1, 0]}},
    {"type": "sphere", "material": "red", "radius": 0.5, "tessellation": [32, 16], "centre": [0, 0, 0]}
  ]
})";

render::AnimatedScene scene_from(const std::string& json) {
    std::vector<std::string> warnings;
    render::AnimatedScene s = scene_file::build_scene(scene_file::parse_scene(json, "test.json", warnings));
    EXPECT_TRUE(warnings.empty());
    return s;
}

Frame render_scene(const std::string& json, int w, int h, render::RendererKind r, render::ShadowMode s, int threads = 0) {
    std::unique_ptr<tbb::global_control> limit;
    if (threads > 0) limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, threads);
    render::AnimatedScene scene = scene_from(json);
    render::FrameRenderer renderer(scene, w, h, r, s);
    return renderer.render(0.5f);
}

// Projects a world point to its pixel in the test camera.
glm::ivec2 pixel_of(glm::vec3 p, int w, int h) {
    Camera c;
    c.eye = {0, 3, 4};
    c.lookat = {0, 0, 0};
    c.fovy_deg = 50;
    c.aspect = float(w) / float(h);
    const glm::vec4 clip = c.view_projection() * glm::vec4(p, 1.0f);
    const glm::vec2 ndc = glm::vec2(clip) / clip.w;
    return {int((ndc.x * 0.5f + 0.5f) * float(w)), int((0.5f - ndc.y * 0.5f) * float(h))};
}

}  // namespace

class RenderShadows : public ::testing::TestWithParam<render::ShadowMode> {};

TEST_P(RenderShadows, DarkenOnlyTheFloorUnderTheBall) {
    const int w = 160, h = 120;
    const Frame lit = render_scene(kBallOverFloor, w, h, render::RendererKind::raster, render::ShadowMode::none);
    const Frame shadowed = render_scene(kBallOverFloor, w, h, render::RendererKind::raster, GetParam());
    // Under the ball (the light is straight above): only ambient ka La remains.
    const glm::ivec2 under = pixel_of({0.0f, -1.0f, 0.3f}, w, h);
    const glm::vec4 a = lit.at(under.x, under.y), b = shadowed.at(under.x, under.y);
    EXPECT_NEAR(b.r, 0.5f * 0.2f, 1e-3f) << "shadowed floor should be ka * La";
    EXPECT_GT(a.r, 0.5f);  // lit: ka La + kd cos(0) Le
    // Far from the ball nothing changes.
    const glm::ivec2 far = pixel_of({2.0f, -1.0f, 1.0f}, w, h);
    EXPECT_EQ(lit.at(far.x, far.y), shadowed.at(far.x, far.y));
    // The ball's own lit top is untouched; its underside faces away from the light and keeps
    // the kernel's smooth falloff (no shadow-ray terminator).
    const glm::ivec2 top = pixel_of({0.0f, 0.45f, 0.2f}, w, h);
    EXPECT_EQ(lit.at(top.x, top.y), shadowed.at(top.x, top.y));
}

INSTANTIATE_TEST_SUITE_P(RenderFrame, RenderShadows, ::testing::Values(render::ShadowMode::rays, render::ShadowMode::map),
                         [](const auto& info) { return info.param == render::ShadowMode::rays ? "rays" : "map"; });

TEST(RenderFrame, RasterAndRayCastAgreeAwayFromEdges) {
    const int w = 160, h = 120;
    for (render::ShadowMode s : {render::ShadowMode::none, render::ShadowMode::rays}) {
        const Frame a = render_scene(kBallOverFloor, w, h, render::RendererKind::raster, s);
        const Frame b = render_scene(kBallOverFloor, w, h, render::RendererKind::raytrace, s);
        size_t differ = 0;
        for (size_t i = 0; i < a.pixels.size(); ++i)
            differ += glm::length(a.pixels[i] - b.pixels[i]) > 2.0f / 255.0f;
        // Only silhouette pixels may differ (coverage at pixel centres exactly on an edge).
        EXPECT_LT(differ, a.pixels.size() / 50) << "mode " << int(s);
    }
}

// Two overlapping glass panes (blue in front of, and submitted after, a red one) and a glass
// ball over the floor: the ray caster passes through them and blends them in submission order
// as the rasterizer does.
const char* kGlass = R"({
  "camera": {"eye": [0, 3, 4], "lookat": [0, 0, 0], "fov": 50},
  "background": {"type": "colour", "colour": [0.2, 0.3, 0.4]},
  "lights": [{"direction": [0.2, 1, 0.5], "La": [0.3, 0.3, 0.3], "Le": [1, 1, 1]}],
  "materials": {"floor": {"model": "phong", "kd": [0.7, 0.7, 0.6], "ka": [0.5, 0.5, 0.5], "ks": [0, 0, 0]},
                "red": {"model": "phong", "kd": [0.9, 0.1, 0.1], "opacity": 0.5},
                "blue": {"model": "phong", "kd": [0.1, 0.2, 0.9], "opacity": 0.4}},
  "objects": [
    {"type": "box", "material": "floor", "size": [6, 0.2, 6], "transform": {"translate": [0, -1.1, 0]}},
    {"type": "box", "material": "red", "size": [1.6, 1.6, 0.05], "transform": {"translate": [-0.4, 0, -0.5]}},
    {"type": "box", "material": "blue", "size": [1.6, 1.6, 0.05], "transform": {"translate": [0.4, 0.2, 0.5]}},
    {"type": "sphere", "material": "blue", "radius": 0.4, "tessellation": [24, 12], "centre": [1.6, -0.5, 0.8]}
  ]
})";

// A sliver thinner than the snapping's reach: its vertex V lies 0.4 sub-pixel right of and
// below the centre of pixel (20, 15) and snaps onto it, A and B lie on the sub-pixel grid, and
// A - V, B - V are nearly opposite. Unsnapped it is clockwise in NDC (twice its area +17.2
// sub-pixels^2: a back face), snapped counter-clockwise (-58: a front face), and it covers
// the pixel centre through V (top-left rule). Its normals follow its world winding, away from
// the eye, and the light shines along them: lit from the side the rasterizer drew, ka La +
// kd Le = 1; lit as the back face its world position shows, only ambient, 0.25.
TEST(RenderFrame, SliverTurnedOverBySnappingIsLitFromTheSideItWasDrawn) {
    const int w = 40, h = 30;
    scene::Scene s;
    s.camera.aspect = float(w) / float(h);
    const glm::vec2 centre(20.5f, 15.5f);
    workloads::WindowMesh window;
    for (const glm::vec2 d : {glm::vec2(0.4f, 0.4f), glm::vec2(-30.0f, 7.0f), glm::vec2(124.0f, -27.0f)})
        window.positions.push_back({centre + d / 256.0f, 0.5f});
    window.indices = {0, 1, 2};
    auto mesh = std::make_shared<Mesh>(workloads::to_world(window, s.camera.view_projection(), w, h));
    const glm::dvec3 p0 = mesh->positions[0], p1 = mesh->positions[1], p2 = mesh->positions[2];
    const glm::vec3 normal = glm::normalize(glm::cross(p1 - p0, p2 - p0));
    EXPECT_LT(glm::dot(glm::dvec3(normal), glm::dvec3(s.camera.eye) - p0), 0.0) << "a back face in world space";
    mesh->normals.assign(3, normal);
    s.lights = {scene::directional_light(normal, glm::vec3(0.25f), glm::vec3(0.75f))};
    scene::Material m;
    m.ka = m.kd = glm::vec3(1.0f);
    m.ks = glm::vec3(0.0f);
    s.materials = {m};
    s.background.colour = glm::vec3(0.0f);
    s.objects = {{"sliver", mesh, 0, {}, {}}};
    render::AnimatedScene scene = render::still_scene(std::move(s));
    render::FrameRenderer renderer(scene, w, h, render::RendererKind::raster, render::ShadowMode::none);
    const Frame f = renderer.render(0.0f);
    EXPECT_NEAR(f.at(20, 15).r, 1.0f, 1e-5f);
    float elsewhere = 0.0f;  // the sliver covers no other pixel centre
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            if (x != 20 || y != 15) elsewhere = std::max(elsewhere, f.at(x, y).r);
    EXPECT_EQ(elsewhere, 0.0f);
}

// A rough heightfield seen at a grazing angle, lit from straight above with no ambient and no
// specular term: every front face has N.L > 0 and shows some red, every back face (lit as its
// underside) is black. A heightfield seen from above shows no back face, and the rays find
// none; the raster must not either. Its silhouettes are folds where a back face meets the
// front face that hides it, sharing an edge and, next to it, nearly its depth; the near plane
// at 0.01 crowds window depth against 1 (z = 1 - 0.01/d), where such pairs round to the same
// value (triangle_setup.h). Grid sizes 101^2 .. 301^2: the specks move but do not go away.
TEST(RenderFrame, RasterShowsNoBackFaceOfAHeightfieldWhereRaysShowNone) {
    for (int samples : {101, 201, 301}) {
        const std::string json = R"({
          "camera": {"eye": [0, 1.2, 8], "lookat": [0, 0.2, 0], "fov": 40, "near": 0.01, "far": 100},
          "background": {"type": "colour", "colour": [0.2, 0.3, 0.9]},
          "lights": [{"direction": [0, 1, 0], "La": [0, 0, 0], "Le": [1, 1, 1]}],
          "materials": {"ground": {"model": "phong", "kd": [0.5, 0.5, 0.5], "ks": [0, 0, 0]}},
          "objects": [{"type": "heightfield", "material": "ground", "relief": "fbm", "cells": 6, "octaves": 8,
                       "samples": [)" + std::to_string(samples) + ", " + std::to_string(samples) + R"(],
                       "size": [20, 20], "height": 1.5, "transform": {"translate": [0, -1.2, 0]}}]
        })";
        const int w = 320, h = 180;
        size_t unlit[2] = {0, 0};
        for (render::RendererKind r : {render::RendererKind::raster, render::RendererKind::raytrace}) {
            const Frame f = render_scene(json, w, h, r, render::ShadowMode::none);
            for (int y = 0; y < h; ++y)
                for (int x = 0; x < w; ++x)
                    if (f.at(x, y).r == 0.0f) {
                        ++unlit[r == render::RendererKind::raytrace];
                        ADD_FAILURE() << samples << "^2 samples, " << (r == render::RendererKind::raster ? "raster" : "rays")
                                      << ": pixel (" << x << ", " << y << ") shows a back face";
                    }
        }
        EXPECT_EQ(unlit[0], 0u) << samples << "^2 samples, raster";
        EXPECT_EQ(unlit[1], 0u) << samples << "^2 samples, rays";
    }
}

TEST(RenderFrame, RayCastBlendsTransparencyAsTheRasterizerDoes) {
    const int w = 160, h = 120;
    const Frame raster = render_scene(kGlass, w, h, render::RendererKind::raster, render::ShadowMode::none);
    const Frame rays = render_scene(kGlass, w, h, render::RendererKind::raytrace, render::ShadowMode::none);
    size_t differ = 0;
    for (size_t i = 0; i < raster.pixels.size(); ++i)
        differ += glm::length(raster.pixels[i] - rays.pixels[i]) > 2.0f / 255.0f;
    EXPECT_LT(differ, raster.pixels.size() / 50);
    // Where the panes overlap, both colours show: the red pane through the blue one.
    const glm::ivec2 p = pixel_of({0.0f, 0.3f, 0.5f}, w, h);
    for (const Frame* f : {&raster, &rays}) {
        const glm::vec4 c = f->at(p.x, p.y);
        EXPECT_GT(c.r, 0.15f) << "red pane not seen through the blue one";
        EXPECT_GT(c.b, c.g) << "blue pane missing";
        EXPECT_FLOAT_EQ(c.a, 1.0f);
    }
}

TEST(RenderFrame, SameBytesWithOneAndTwoThreads) {
    for (render::ShadowMode s : {render::ShadowMode::none, render::ShadowMode::rays, render::ShadowMode::map})
        for (render::RendererKind r : {render::RendererKind::raster, render::RendererKind::raytrace}) {
            const Frame one = render_scene(kBallOverFloor, 96, 64, r, s, 1);
            const Frame two = render_scene(kBallOverFloor, 96, 64, r, s, 2);
            ASSERT_EQ(one.pixels.size(), two.pixels.size());
            EXPECT_EQ(0, std::memcmp(one.pixels.data(), two.pixels.data(), one.pixels.size() * sizeof(glm::vec4)));
        }
}

// An animation renders every frame into one reused buffer: what it held before (another
// frame, another size, garbage) must not show, for either renderer, with or without set_rows.
TEST(RenderFrame, AReusedFrameBufferGivesTheSameBytesAsAFreshOne) {
    for (render::RendererKind r : {render::RendererKind::raster, render::RendererKind::raytrace})
        for (const bool rows : {false, true}) {
            render::AnimatedScene scene = scene_from(kBallOverFloor);
            render::FrameRenderer renderer(scene, 96, 64, r, render::ShadowMode::rays);
            if (rows) renderer.set_rows(10, 40);
            const Frame fresh = renderer.render(0.5f);
            Frame reused(96, 64, glm::vec4(std::numeric_limits<float>::quiet_NaN()));
            renderer.render(0.1f, reused);
            renderer.render(0.5f, reused);
            Frame resized(7, 3, glm::vec4(9.0f));
            renderer.render(0.5f, resized);
            for (const Frame* f : {&reused, &resized}) {
                ASSERT_EQ(f->width, 96);
                ASSERT_EQ(f->height, 64);
                ASSERT_EQ(f->pixels.size(), fresh.pixels.size());
                EXPECT_EQ(0, std::memcmp(f->pixels.data(), fresh.pixels.data(), fresh.pixels.size() * sizeof(glm::vec4)))
                    << int(r) << " rows " << rows;
            }
        }
}

// The 8-bit frame encoded tile by tile (render_srgb8) is encode_srgb8 of the float frame, byte
// for byte: both renderers, one and four samples, restricted rows, shadows, toon outlines
// (inked after encoding), a buffer reused at another size; NaN pixels are counted.
TEST(RenderFrame, EightBitFramesAreTheEncodedFloatFrames) {
    const std::string toon = R"({
  "camera": {"eye": [0, 3, 4], "lookat": [0, 0, 0], "fov": 50},
  "background": {"type": "sky"},
  "lights": [{"direction": [0.3, 1, 0.2], "La": [0.2, 0.2, 0.2], "Le": [1, 1, 1]}],
  "materials": {"grey": {"model": "phong", "kd": [0.6, 0.6, 0.6]}, "ink": {"model": "toon", "kd": [0.9, 0.4, 0.1]}},
  "objects": [
    {"type": "box", "material": "grey", "size": [6, 0.2, 6], "transform": {"translate": [0, -1.1, 0]}},
    {"type": "sphere", "material": "ink", "radius": 0.5, "tessellation": [32, 16], "centre": [0, 0, 0]}
  ]
})";
    for (const std::string& json : {std::string(kBallOverFloor), toon})
        for (render::RendererKind r : {render::RendererKind::raster, render::RendererKind::raytrace})
            for (const int samples : {1, 4})
                for (const bool rows : {false, true}) {
                    SCOPED_TRACE("renderer " + std::to_string(int(r)) + ", samples " + std::to_string(samples) +
                                 ", rows " + std::to_string(rows));
                    render::AnimatedScene scene = scene_from(json);
                    render::FrameRenderer renderer(scene, 99, 70, r, render::ShadowMode::rays, samples);
                    if (rows) renderer.set_rows(10, 40);
                    const Frame frame = renderer.render(0.5f);
                    std::vector<uint8_t> expected(frame.pixels.size() * 4);
                    ASSERT_TRUE(output::encode_srgb8(frame.pixels.data(), frame.pixels.size(), expected.data()));
                    std::vector<uint8_t> bytes(5, 7);
                    EXPECT_EQ(renderer.render_srgb8(0.5f, bytes), 0u);
                    EXPECT_EQ(bytes, expected);
                }
}

TEST(RenderFrame, RejectsWhatItCannotDo) {
    render::AnimatedScene scene = scene_from(kBallOverFloor);
    EXPECT_THROW(render::FrameRenderer(scene, 0, 10, render::RendererKind::raster, render::ShadowMode::none), std::invalid_argument);
    EXPECT_THROW(render::parse_renderer("gpu"), std::invalid_argument);
    EXPECT_THROW(render::parse_shadow_mode("soft"), std::invalid_argument);
}

TEST(RenderFrame, TraceHasWorkerTracksAndStageAndTileSlices) {
    const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
    render::AnimatedScene scene = scene_from(kBallOverFloor);
    render::FrameRenderer renderer(scene, 256, 192, render::RendererKind::raster, render::ShadowMode::rays);
    Trace trace;
    trace.activate();
    {
        TraceScope frame("frame", "frame", 1);
        renderer.render(0.0f);
    }
    trace.deactivate();
    const fs::path path = fs::temp_directory_path() / ("tessera_trace_" + std::to_string(::getpid()) + ".json");
    trace.write(path);
    std::ifstream in(path);
    const nlohmann::json doc = nlohmann::json::parse(in);  // throws if the JSON is not valid
    fs::remove(path);
    std::set<std::string> names;
    std::set<int> tracks, named_tracks;
    for (const auto& e : doc.at("traceEvents")) {
        if (e.at("ph") == "M") {
            if (e.at("name") == "thread_name") named_tracks.insert(e.at("tid").get<int>());
            continue;
        }
        EXPECT_EQ(e.at("ph"), "X");
        EXPECT_GE(e.at("dur").get<double>(), 0.0);
        names.insert(e.at("name").get<std::string>());
        tracks.insert(e.at("tid").get<int>());
    }
    for (const char* n : {"frame", "animate", "bake", "bvh", "vertex stage", "setup+bin chunk", "raster tile", "tile",
                          "shade", "shadow test"})
        EXPECT_TRUE(names.count(n)) << "no slice named " << n;
    // Which workers pick up tiles is the scheduler's choice (one may be busy elsewhere), so
    // only "at least one track, each named" is guaranteed.
    EXPECT_GE(tracks.size(), 1u);
    for (int t : tracks) EXPECT_TRUE(named_tracks.count(t)) << "track " << t << " has no thread_name";
}
