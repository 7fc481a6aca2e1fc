// The frame renderer keeps the BVH of objects that do not move from frame to frame: an
// animation rendered by one renderer has the same bytes, frame by frame, as each frame
// rendered by a renderer of its own (which builds every BVH afresh), for the ray-cast
// renderer and for the rasterizer's shadow rays, at one and two threads, whatever order the
// frames come in; and it does rebuild only the objects that moved.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cstring>
#include <string>
#include <vector>

#include "raster/render/frame_renderer.h"
#include "raster/scene_file/scene_build.h"
#include "raster/scene_file/scene_parse.h"

using namespace tessera;

namespace {

// Static: a floor, a ball, a glass pane (transparent: the ray-cast renderer collects it by a
// filter). Moving: a spinning torus (rigid) and a snake (deforming). One light casts shadows.
const char* kStaticAndMoving = R"({
  "camera": {"eye": [0, 2.2, 4.5], "lookat": [0, 0, 0], "fov": 45, "orbit": 20},
  "background": {"type": "colour", "colour": [0.3, 0.35, 0.4]},
  "lights": [{"direction": [0.3, 1, 0.4], "La": [0.2, 0.2, 0.2], "Le": [1, 1, 1]}],
  "materials": {"floor": {"model": "phong", "kd": [0.7, 0.7, 0.6], "ka": [0.5, 0.5, 0.5], "ks": [0, 0, 0]},
                "red": {"model": "phong", "kd": [0.8, 0.1, 0.1]},
                "teal": {"model": "phong", "kd": [0.1, 0.6, 0.6]},
                "ink": {"model": "phong", "kd": [0.05, 0.05, 0.05]},
                "glass": {"model": "phong", "kd": [0.1, 0.2, 0.9], "opacity": 0.4}},
  "objects": [
    {"type": "box", "material": "floor", "size": [6, 0.2, 6], "transform": {"translate": [0, -1.0, 0]}},
    {"type": "sphere", "material": "red", "radius": 0.5, "tessellation": [24, 12], "centre": [1.2, -0.4, 0.3]},
    {"type": "torus", "material": "red", "major": 0.6, "minor": 0.2, "tessellation": [32, 12],
     "transform": {"axis": [1, 0, 0], "angle": 25, "translate": [-1.2, 0.0, 0]}, "spin": {"axis": [0, 1, 0], "speed": 90}},
    {"type": "snake", "material": "teal", "eye_material": "ink", "centre": [0.0, 0.6], "path_radii": [1.2, 0.4],
     "speed": 1.0, "length": 2.0, "width": 0.12, "wiggle": 0.2, "wiggle_period": 1.2,
     "transform": {"translate": [0, -0.85, 0]}},
    {"type": "box", "material": "glass", "size": [1.2, 1.2, 0.05], "transform": {"translate": [0.3, 0.1, 1.2]}}
  ]
})";

render::AnimatedScene scene() {
    std::vector<std::string> warnings;
    return scene_file::build_scene(scene_file::parse_scene(kStaticAndMoving, "test.json", warnings));
}

bool same_bytes(const Frame& a, const Frame& b) {
    return a.pixels.size() == b.pixels.size() &&
           std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(glm::vec4)) == 0;
}

struct Case {
    render::RendererKind renderer;
    render::ShadowMode shadows;
};

TEST(RenderStaticBvh, AnAnimationHasTheBytesOfFramesRenderedAfresh) {
    const int w = 96, h = 64;
    // Not in time order: going back in time must not matter either.
    const std::vector<float> times = {0.0f, 0.3f, 0.6f, 0.15f};
    for (const Case c : {Case{render::RendererKind::raytrace, render::ShadowMode::rays},
                         Case{render::RendererKind::raster, render::ShadowMode::rays}}) {
        // The animation on two threads, each fresh frame on one.
        std::vector<Frame> animation;
        std::vector<render::FrameStats> stats(times.size());
        {
            const tbb::global_control two(tbb::global_control::max_allowed_parallelism, 2);
            render::AnimatedScene s = scene();
            render::FrameRenderer renderer(s, w, h, c.renderer, c.shadows);
            for (size_t i = 0; i < times.size(); ++i) animation.push_back(renderer.render(times[i], &stats[i]));
        }
        const tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
        for (size_t i = 0; i < times.size(); ++i) {
            render::AnimatedScene s = scene();
            render::FrameRenderer renderer(s, w, h, c.renderer, c.shadows);
            EXPECT_TRUE(same_bytes(animation[i], renderer.render(times[i])))
                << "renderer " << int(c.renderer) << ", frame at t = " << times[i];
        }
        // The first frame builds every object; later ones only the torus and the snake (the
        // snake's eyes are objects of their own, moving with it).
        EXPECT_EQ(stats[0].bvh_objects_built, stats[0].bvh_objects);
        for (size_t i = 1; i < times.size(); ++i) {
            EXPECT_GE(stats[i].bvh_objects_built, 2u) << "frame " << i;
            EXPECT_LE(stats[i].bvh_objects_built, stats[i].bvh_objects - 3) << "frame " << i;
        }
        EXPECT_FALSE(same_bytes(animation[0], animation[1]));  // the frames do move
    }
}

}  // namespace
