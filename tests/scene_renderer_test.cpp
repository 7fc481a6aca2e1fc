// The scene renderer: the same shading through the tile rasterizer instead of the test's
// brute-force visibility, transparency through the raster core's per-tile transparent pass,
// and the same bytes whatever the thread count.
#include <gtest/gtest.h>

#include <tbb/global_control.h>

#include <cstring>

#include "raster/shade/scene_renderer.h"
#include "shading_harness.h"
#include "shading_scenes.h"

using namespace tessera;
using namespace tessera::test;

namespace {

// Fraction of pixels whose colour differs by more than 3/255 in some channel (sRGB).
double differing(const Frame& a, const Frame& b) {
    const auto ea = encode_srgb8(a), eb = encode_srgb8(b);
    size_t bad = 0;
    for (size_t i = 0; i < ea.size(); i += 4)
        for (int c = 0; c < 4; ++c)
            if (std::abs(int(ea[i + size_t(c)]) - int(eb[i + size_t(c)])) > 3) {
                ++bad;
                break;
            }
    return double(bad) / double(ea.size() / 4);
}

Scene transparent_scene() {
    Scene s = base_scene(coloured(ShadingModel::phong));
    Material glass = coloured(ShadingModel::phong);
    glass.kd = glass.ka = {0.2f, 0.5f, 0.9f};
    glass.opacity = 0.4f;
    s.materials.push_back(glass);
    s.objects.push_back(Object{"ring", std::make_shared<const Mesh>(tessellate(torus_surface(1.2f, 0.15f), 32, 8)),
                               1, {}, {}});
    s.objects[1].transform.axis = {1, 0, 0};
    s.objects[1].transform.angle = 0.5f;
    s.objects[1].transform.translation = {0, 0, 0.6f};
    return s;
}

}  // namespace

TEST(SceneRenderer, RasterizedFramesMatchTheBruteForceShading) {
    SceneRenderer renderer;
    for (ShadingModel model : {ShadingModel::flat, ShadingModel::gouraud, ShadingModel::phong, ShadingModel::toon}) {
        const Scene scene = base_scene(coloured(model));
        // Only silhouette pixels may differ (the fill rule vs the ray test at exact edges).
        EXPECT_LT(differing(renderer.render(scene, 128, 128), render(scene, 128, 128)), 0.01)
            << to_string(model);
    }
}

TEST(SceneRenderer, TransparencyThroughTheTilePassMatches) {
    SceneRenderer renderer;
    const Scene scene = transparent_scene();
    // The brute-force harness blends both triangles on a shared edge; the rasterizer's fill
    // rule gives each edge pixel to one, so a few more pixels differ here.
    EXPECT_LT(differing(renderer.render(scene, 128, 128), render(scene, 128, 128)), 0.03);
}

TEST(SceneRenderer, SameBytesWhateverTheThreadCountAndTileSize) {
    const Scene scene = transparent_scene();
    Frame one;
    {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
        SceneRenderer renderer;
        one = renderer.render(scene, 160, 96);
    }
    SceneRenderer renderer;
    SceneRenderOptions options;
    options.tile_size = 16;
    const Frame many = renderer.render(scene, 160, 96, options);
    ASSERT_EQ(one.pixels.size(), many.pixels.size());
    EXPECT_EQ(0, std::memcmp(one.pixels.data(), many.pixels.data(), one.pixels.size() * sizeof(glm::vec4)));
}
