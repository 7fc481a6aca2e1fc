// The picture of `tessera raster --shade depth` (depth_view.h): visible distances mapped
// linearly from white (nearest) to kFarGrey (farthest), background black.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "raster/core/camera.h"
#include "raster/pipeline/rasterizer.h"
#include "raster/shade/depth_view.h"

namespace tessera::shade {
namespace {

// A floor from 2 to 40 units ahead seen from 1 unit above it: most of its window depths lie
// above 0.99, which grey = window depth showed as white.
TEST(DepthView, AFloorSpansWhiteToTheFarGrey) {
    Mesh floor;
    floor.positions = {{-30, 0, -2}, {30, 0, -2}, {30, 0, -40}, {-30, 0, -40}};
    floor.indices = {0, 1, 2, 0, 2, 3};
    Camera camera;
    camera.eye = {0, 1, 0};
    camera.lookat = {0, 0.2f, -10};
    camera.aspect = 1.0f;
    const int size = 96;
    VisibilityBuffer visibility;
    pipeline::Rasterizer rasterizer;
    rasterizer.render(floor, camera.view_projection(), pipeline::Viewport(size, size), pipeline::RasterOptions{},
                      visibility);
    std::vector<uint8_t> rgb8;
    depth_view(visibility, camera, rgb8);
    ASSERT_EQ(rgb8.size(), size_t(size) * size * 3);

    int lightest = 0, darkest = 255, background = 0;
    int previous = -1;  // the floor's column in the middle: nearer (lighter) going down
    for (int y = 0; y < size; ++y) {
        const size_t i = size_t(y) * size + size / 2;
        const uint8_t grey = rgb8[3 * i];
        EXPECT_EQ(rgb8[3 * i + 1], grey);
        EXPECT_EQ(rgb8[3 * i + 2], grey);
        if (visibility.triangle[i] == kNoTriangle) {
            EXPECT_EQ(grey, 0) << "row " << y;
            ++background;
            continue;
        }
        EXPECT_GE(int(grey), previous) << "row " << y;
        previous = grey;
    }
    for (size_t i = 0; i < size_t(size) * size; ++i)
        if (visibility.triangle[i] != kNoTriangle) {
            lightest = std::max<int>(lightest, rgb8[3 * i]);
            darkest = std::min<int>(darkest, rgb8[3 * i]);
        }
    EXPECT_GT(background, 0);  // the sky above the far edge
    EXPECT_EQ(lightest, 255);
    EXPECT_EQ(darkest, int(kFarGrey));
}

TEST(DepthView, OneDepthIsWhiteAndNothingCoveredIsBlack) {
    Mesh wall;
    wall.positions = {{-1, -1, -5}, {1, -1, -5}, {1, 1, -5}};
    wall.indices = {0, 1, 2};
    Camera camera;
    camera.eye = {0, 0, 0};
    camera.lookat = {0, 0, -1};
    camera.aspect = 1.0f;
    VisibilityBuffer visibility;
    pipeline::Rasterizer rasterizer;
    rasterizer.render(wall, camera.view_projection(), pipeline::Viewport(32, 32), pipeline::RasterOptions{},
                      visibility);
    std::vector<uint8_t> rgb8;
    depth_view(visibility, camera, rgb8);
    size_t white = 0;
    for (size_t i = 0; i < visibility.triangle.size(); ++i)
        if (visibility.triangle[i] != kNoTriangle) {
            EXPECT_EQ(rgb8[3 * i], 255);
            ++white;
        } else {
            EXPECT_EQ(rgb8[3 * i], 0);
        }
    EXPECT_GT(white, 50u);

    VisibilityBuffer empty;
    empty.reset(8, 4);
    depth_view(empty, camera, rgb8);
    EXPECT_EQ(rgb8, std::vector<uint8_t>(8 * 4 * 3, 0));
}

}  // namespace
}  // namespace tessera::shade
