// The shading scenes through the frame path (FrameRenderer: tile rasterizer, per-tile shading
// and transparency) agree with the brute-force visibility of the golden tests, and give the
// same bytes whatever the thread count.
#include <gtest/gtest.h>

#include <tbb/global_control.h>

#include <cstring>

#include "shading_harness.h"
#include "shading_scenes.h"

using namespace tessera;
using namespace tessera::test;

namespace {

// Fraction of pixels whose colour differs by more than 3/255 in some channel (sRGB).
double differing(const Frame& a, const Frame& b) {
    return double(count_differing(output::encode_srgb8(a), output::encode_srgb8(b), 3)) / double(a.pixels.size());
}

}  // namespace

TEST(ShadingRaster, RasterizedFramesMatchTheBruteForceShading) {
    for (scene::ShadingModel model : {scene::ShadingModel::flat, scene::ShadingModel::gouraud, scene::ShadingModel::phong, scene::ShadingModel::toon}) {
        const scene::Scene scene = base_scene(coloured(model));
        // Only silhouette pixels may differ (the fill rule vs the ray test at exact edges).
        EXPECT_LT(differing(rasterize(scene, 128, 128), render_scene(scene, 128, 128)), 0.01) << to_string(model);
    }
}

TEST(ShadingRaster, TransparencyThroughTheTilePassMatches) {
    const scene::Scene scene = transparent_scene();
    // The brute-force harness blends both triangles on a shared edge; the rasterizer's fill
    // rule gives each edge pixel to one, so a few more pixels differ here.
    EXPECT_LT(differing(rasterize(scene, 128, 128), render_scene(scene, 128, 128)), 0.03);
}

// The tile size is the rasterizer's (RasterPipeline.TransparentFragmentsInSubmissionOrder
// checks the transparent fragments do not depend on it); this checks the shading on top.
TEST(ShadingRaster, SameBytesWhateverTheThreadCount) {
    const scene::Scene scene = transparent_scene();
    Frame one;
    {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
        one = rasterize(scene, 160, 96);
    }
    const Frame many = rasterize(scene, 160, 96);
    ASSERT_EQ(one.pixels.size(), many.pixels.size());
    EXPECT_EQ(0, std::memcmp(one.pixels.data(), many.pixels.data(), one.pixels.size() * sizeof(glm::vec4)));
}
