// Toon outlines from the visibility buffer (shade/outline.h): unbroken on a thin body where the
// shader's |N.V| band is thinner than a pixel, never on a plane however grazing, only on toon
// materials, and the same whichever way the rows are split.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <string>
#include <vector>

#include "raster/render/frame_renderer.h"
#include "raster/scene_file/scene_build.h"
#include "raster/scene_file/scene_parse.h"
#include "raster/shade/outline.h"

using namespace tessera;

namespace {

constexpr int W = 48, H = 32;

Camera test_camera() {
    Camera c;
    c.near = 0.5f;
    c.far = 50.0f;
    return c;
}

// Window depth of view distance d for the camera above.
float window_depth(float d) {
    const Camera c = test_camera();
    const float z_ndc = (c.far + c.near - 2.0f * c.near * c.far / d) / (c.far - c.near);
    return z_ndc * 0.5f + 0.5f;
}

// A floor seen from above at a grazing angle: 1/d is affine across the screen, steeply.
VisibilityBuffer grazing_floor() {
    VisibilityBuffer v;
    v.reset(W, H);
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            const float inverse_distance = 0.025f + 0.025f * float(y) + 0.001f * float(x);
            v.depth[size_t(y) * W + x] = window_depth(1.0f / inverse_distance);
            v.triangle[size_t(y) * W + x] = 0;
        }
    return v;
}

std::vector<scene::Material> toon_and_phong() {
    scene::Material toon, phong;
    toon.model = scene::ShadingModel::toon;
    return {toon, phong};
}

std::vector<glm::vec4> white() { return std::vector<glm::vec4>(size_t(W) * H, glm::vec4(1.0f)); }

bool black(const glm::vec4& c) { return c.r == 0.0f && c.g == 0.0f && c.b == 0.0f; }

}  // namespace

TEST(ShadingOutline, APlaneIsNeverInkedHoweverGrazing) {
    const VisibilityBuffer floor = grazing_floor();
    const std::vector<uint32_t> triangle_material{0};
    std::vector<glm::vec4> colour = white();
    shade::draw_outlines(floor, test_camera(), triangle_material, toon_and_phong(), colour, 0, H);
    for (size_t i = 0; i < colour.size(); ++i) ASSERT_FALSE(black(colour[i])) << "pixel " << i % W << "," << i / W;
}

TEST(ShadingOutline, AStripInFrontOfTheFloorIsOutlinedAlongItsWholeLength) {
    VisibilityBuffer v = grazing_floor();
    // Rows 10..12: a 3-pixel strip 5 units away, in front of the floor (triangle 1).
    for (int y = 10; y <= 12; ++y)
        for (int x = 0; x < W; ++x) {
            v.depth[size_t(y) * W + x] = window_depth(5.0f);
            v.triangle[size_t(y) * W + x] = 1;
        }
    // The floor around the strip is farther than the strip: 1/d below 0.2 there.
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x)
            if (v.triangle[size_t(y) * W + x] == 0) v.depth[size_t(y) * W + x] = window_depth(20.0f + float(y));
    v.depth[size_t(3) * W + 7] = 1.0f;  // and one background pixel in the floor
    v.triangle[size_t(3) * W + 7] = kNoTriangle;
    const std::vector<uint32_t> triangle_material{1, 0};  // floor phong, strip toon
    std::vector<glm::vec4> colour = white();
    shade::draw_outlines(v, test_camera(), triangle_material, toon_and_phong(), colour, 0, H);
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            const bool expected = y == 10 || y == 12;  // the strip's rows next to the floor
            EXPECT_EQ(black(colour[size_t(y) * W + x]), expected) << x << "," << y;
        }
    // Bands of rows give the same pixels as the whole frame.
    std::vector<glm::vec4> banded = white();
    for (int y0 = 0; y0 < H; y0 += 11)
        shade::draw_outlines(v, test_camera(), triangle_material, toon_and_phong(), banded, y0, std::min(H, y0 + 11));
    EXPECT_EQ(banded, colour);
    // Phong materials get no outline.
    std::vector<glm::vec4> untouched = white();
    const std::vector<scene::Material> phong_only(2);
    shade::draw_outlines(v, test_camera(), triangle_material, phong_only, untouched, 0, H);
    EXPECT_EQ(untouched, white());
}

namespace {

// A thin rod (0.24 units across, ~6 pixels) against the background, its right half in front
// of a box. With `model` toon the rod is outlined.
std::string rod_scene(const std::string& model) {
    return R"({
  "camera": {"eye": [0, 0, 4], "lookat": [0, 0, 0], "fov": 45},
  "background": {"type": "colour", "colour": [0.2, 0.3, 0.9]},
  "lights": [{"direction": [0.3, 1, 0.6], "La": [0.2, 0.2, 0.2], "Le": [1, 1, 1]}],
  "materials": {"rod": {"model": ")" + model + R"(", "kd": [0.1, 0.8, 0.1], "ka": [0.1, 0.8, 0.1]},
                "box": {"model": "phong", "kd": [0.8, 0.1, 0.1], "ka": [0.8, 0.1, 0.1]}},
  "objects": [
    {"type": "ellipsoid", "material": "rod", "radii": [1.3, 0.12, 0.12], "tessellation": [48, 16],
     "centre": [0, 0, 0], "transform": {"axis": [0, 0, 1], "angle": 12}},
    {"type": "box", "material": "box", "size": [1.2, 1.2, 0.1], "transform": {"translate": [0.9, 0, -1.5]}}
  ]
})";
}

Frame render_rod(const std::string& model, render::RendererKind kind) {
    std::vector<std::string> warnings;
    render::AnimatedScene scene = scene_file::build_scene(scene_file::parse_scene(rod_scene(model), "rod.json", warnings));
    render::FrameRenderer renderer(scene, 240, 150, kind, render::ShadowMode::none);
    return renderer.render(0.0f);
}

}  // namespace

// The toon shader's own silhouette (|N.V| < 0.2) is a sliver of a pixel on the thin rod and
// breaks into dashes; every rod pixel beside the background or the box behind must be ink.
TEST(ShadingOutline, AThinToonRodHasAnUnbrokenOutlineInBothRenderers) {
    for (const render::RendererKind kind : {render::RendererKind::raster, render::RendererKind::raytrace}) {
        // Which pixel shows what, from the same geometry with the rod in Phong.
        const Frame plain = render_rod("phong", kind), toon = render_rod("toon", kind);
        const auto rod = [&](int x, int y) {
            const glm::vec4 c = plain.pixels[size_t(y) * plain.width + x];
            return c.g > c.r && c.g > c.b;
        };
        int edge = 0, inked = 0, inside = 0, inside_inked = 0;
        for (int y = 1; y + 1 < plain.height; ++y)
            for (int x = 1; x + 1 < plain.width; ++x) {
                if (!rod(x, y)) continue;
                const bool on_edge = !rod(x - 1, y) || !rod(x + 1, y) || !rod(x, y - 1) || !rod(x, y + 1);
                const bool ink = black(toon.pixels[size_t(y) * toon.width + x]);
                (on_edge ? edge : inside)++;
                (on_edge ? inked : inside_inked) += ink;
            }
        EXPECT_GT(edge, 150);
        EXPECT_EQ(inked, edge) << "rod pixels beside something farther left without ink";
        EXPECT_GT(inside - inside_inked, inside / 3) << "the rod's inside keeps its colour";
    }
}

// OutlinePass (rows prepared once) against the pixel-by-pixel definition, on buffers with
// every kind of neighbour: planes at random slopes and depths, background, pixels without a
// triangle's material, toon and Phong materials, split into uneven row blocks.
TEST(ShadingOutline, TheRowPassEqualsTheReferenceOnRandomBuffers) {
    std::mt19937 rng(17);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    const std::vector<scene::Material> materials = toon_and_phong();
    const std::vector<uint32_t> triangle_material{0, 1, 0, 0, 1};  // ids 5+ have no material
    for (int trial = 0; trial < 20; ++trial) {
        VisibilityBuffer v = grazing_floor();
        // Rectangles of planes (1/d affine in x and y), some background, some unknown ids.
        for (int r = 0; r < 12; ++r) {
            const int x0 = int(rng() % W), y0 = int(rng() % H);
            const int x1 = std::min(W, x0 + 1 + int(rng() % 20)), y1 = std::min(H, y0 + 1 + int(rng() % 12));
            const uint32_t id = uint32_t(rng() % 7);
            const float base = 0.02f + 0.5f * unit(rng), dx = 0.01f * (unit(rng) - 0.5f), dy = 0.01f * (unit(rng) - 0.5f);
            const bool background = rng() % 6 == 0;
            for (int y = y0; y < y1; ++y)
                for (int x = x0; x < x1; ++x) {
                    const size_t i = size_t(y) * W + size_t(x);
                    v.triangle[i] = background ? kNoTriangle : id;
                    v.depth[i] = background ? 1.0f : window_depth(1.0f / std::max(0.021f, base + dx * float(x) + dy * float(y)));
                }
        }
        std::vector<glm::vec4> expected = white(), whole = white(), banded = white();
        shade::draw_outlines_reference(v, test_camera(), triangle_material, materials, expected, 0, H);
        shade::draw_outlines(v, test_camera(), triangle_material, materials, whole, 0, H);
        const shade::OutlinePass pass(v, test_camera(), triangle_material, materials);
        for (int y0 = 0; y0 < H; y0 += 1 + trial % 7) pass.run(banded, y0, y0 + 1 + trial % 7);
        ASSERT_EQ(whole, expected) << "trial " << trial;
        ASSERT_EQ(banded, expected) << "trial " << trial;
    }
}
