// --stats' tile stage by pass: every pass that runs is timed, the ones that do not run cost
// nothing, the passes never add up to more than the whole tiles, and asking for the times
// does not change a byte of the frame. No timing value is asserted beyond that.
#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <vector>

#include "raster/render/frame_renderer.h"
#include "raster/render/tile_pass_times.h"
#include "raster/scene_file/scene_build.h"
#include "raster/scene_file/scene_parse.h"

using namespace tessera;

namespace {

// Opaque, glass and toon objects over a floor, a sky, fog, one shadow-casting light: every pass
// but the ray-marched surfaces runs.
const char* kPasses = R"({
  "camera": {"eye": [0, 2.5, 4.5], "lookat": [0, 0, 0], "fov": 50},
  "background": {"type": "sky"},
  "lights": [{"direction": [0.3, 1, 0.4], "La": [0.2, 0.2, 0.2], "Le": [1, 1, 1]}],
  "materials": {"floor": {"model": "phong", "kd": [0.7, 0.7, 0.6]},
                "red": {"model": "phong", "kd": [0.8, 0.1, 0.1]},
                "glass": {"model": "phong", "kd": [0.1, 0.2, 0.9], "opacity": 0.4},
                "ink": {"model": "toon", "kd": [0.9, 0.8, 0.1]}},
  "objects": [
    {"type": "box", "material": "floor", "size": [4, 0.2, 4], "transform": {"translate": [0, -1.0, 0]}},
    {"type": "sphere", "material": "red", "radius": 0.5, "tessellation": [24, 12], "centre": [0.6, -0.4, 0]},
    {"type": "sphere", "material": "ink", "radius": 0.3, "tessellation": [16, 8], "centre": [-0.9, -0.6, -0.5]},
    {"type": "box", "material": "glass", "size": [1.2, 1.2, 0.05], "transform": {"translate": [-0.3, 0.1, 1.0]}}
  ],
  "passes": [{"type": "fog", "density": [0.05, 0.05, 0.05]}]
})";

render::AnimatedScene scene() {
    std::vector<std::string> warnings;
    return scene_file::build_scene(scene_file::parse_scene(kPasses, "test.json", warnings));
}

TEST(TilePassTimes, EveryPassThatRunsIsTimedAndTheyAddUpToAtMostTheTiles) {
    for (const render::RendererKind r : {render::RendererKind::raster, render::RendererKind::raytrace})
        for (const int samples : {1, 4}) {
            SCOPED_TRACE("renderer " + std::to_string(int(r)) + ", samples " + std::to_string(samples));
            render::AnimatedScene s = scene();
            render::FrameRenderer renderer(s, 96, 64, r, render::ShadowMode::rays, samples);
            render::FrameStats stats;
            const Frame timed = renderer.render(0.0f, &stats);
            const Frame untimed = renderer.render(0.0f);
            ASSERT_EQ(timed.pixels.size(), untimed.pixels.size());
            EXPECT_EQ(0, std::memcmp(timed.pixels.data(), untimed.pixels.data(), timed.pixels.size() * sizeof(glm::vec4)));

            const render::TilePassTimes& t = stats.tile_passes;
            for (size_t p = 0; p < render::kTilePasses; ++p) EXPECT_GE(t.ms[p], 0.0) << render::tile_pass_name(render::TilePass(p));
            for (const render::TilePass ran : {render::TilePass::shade, render::TilePass::background,
                                               render::TilePass::transparent, render::TilePass::shadows,
                                               render::TilePass::blend, render::TilePass::fog,
                                               render::TilePass::outline})
                EXPECT_GT(t[ran], 0.0) << render::tile_pass_name(ran);
            EXPECT_EQ(t[render::TilePass::terrain], 0.0);
            EXPECT_EQ(t[render::TilePass::metaballs], 0.0);
            // Each pass lies inside its tile's interval on the same clock (nanosecond sums).
            EXPECT_LE(t.passes_ms(), t.tiles_ms * (1.0 + 1e-12));
        }
}

TEST(TilePassTimes, EveryPassHasAName) {
    std::vector<std::string> names;
    for (size_t p = 0; p < render::kTilePasses; ++p) {
        const std::string name(render::tile_pass_name(render::TilePass(p)));
        EXPECT_NE(name, "?");
        for (const std::string& other : names) EXPECT_NE(name, other);
        names.push_back(name);
    }
}

}  // namespace
