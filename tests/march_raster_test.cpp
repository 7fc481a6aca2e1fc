// Marched surfaces inside the rasterizer's tile stage: a rasterized quad and a marched sphere
// occlude each other per pixel by true distance, the triangle id is cleared where the sphere
// wins, fog covers both, and the frame is byte-identical for any thread count and tile size.
#include <gtest/gtest.h>

#include <tbb/global_control.h>

#include <cmath>
#include <cstring>
#include <optional>
#include <vector>

#include "raster/march/fog_pass.h"
#include "raster/march/tile_passes.h"
#include "raster/pipeline/rasterizer.h"
#include "march_fixtures.h"

using namespace tessera;
using namespace tessera::march;
using namespace tessera::test;

namespace {

constexpr int W = 96, H = 64;
const glm::vec4 kGreen(0.0f, 1.0f, 0.0f, 1.0f);

// A quad in the plane z = 0.9 over x in [-4, 0]: in front of most of the sphere, behind
// the cap that reaches z = 1.
Mesh quad() {
    Mesh m;
    m.positions = {{-4.0f, -4.0f, 0.9f}, {0.0f, -4.0f, 0.9f}, {0.0f, 4.0f, 0.9f}, {-4.0f, 4.0f, 0.9f}};
    m.indices = {0, 1, 2, 0, 2, 3};
    return m;
}

// Paints covered pixels green: stands in for the opaque shading pass.
void paint(const pipeline::TileContext& tile) {
    for (int y = 0; y < tile.height(); ++y)
        for (int x = 0; x < tile.width(); ++x)
            if (tile.triangle[y * tile.stride + x] != kNoTriangle) tile.colour[y * tile.colour_stride + x] = kGreen;
}

struct Result {
    VisibilityBuffer vis;
    std::vector<glm::vec4> colour;
};

Result render_scene(int tile_size, const Fog* fog) {
    const Camera cam = march_camera(W, H);
    const RayGenerator rays(cam, W, H);
    const scene::Background background{};
    const auto sphere = sphere_pass(rays, background);
    std::vector<pipeline::TilePass> passes{paint, tile_pass(sphere)};
    std::optional<FogPass> fog_pass;
    if (fog) passes.push_back(tile_pass(fog_pass.emplace(rays, *fog)));
    pipeline::RasterOptions options;
    options.tile_size = tile_size;
    Result r;
    pipeline::Rasterizer rasterizer;
    rasterizer.render(quad(), cam.view_projection(), pipeline::Viewport(W, H), options, r.vis, passes, &r.colour);
    return r;
}

}  // namespace

TEST(MarchRaster, MarchedSphereAndRasterizedQuadOccludeEachOther) {
    const Result r = render_scene(64, nullptr);
    const Camera cam = march_camera(W, H);
    const RayGenerator rays(cam, W, H);
    int sphere_wins = 0, quad_wins = 0;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            const glm::vec3 d = rays.direction(x, y);
            const double ts = unit_sphere_distance(cam.eye, d);
            const double tq = (0.9 - cam.eye.z) / d.z;
            const glm::vec3 hit_quad = cam.eye + d * float(tq);
            const bool on_quad = hit_quad.x < -0.01f;  // clear of the quad's edge x = 0
            const bool grazing = !std::isinf(ts) && ts > 3.6;
            if (grazing || std::fabs(hit_quad.x) <= 0.01f || (on_quad && std::fabs(ts - tq) < 0.02)) continue;
            const size_t i = size_t(y) * W + x;
            const bool sphere_visible = !std::isinf(ts) && (!on_quad || ts < tq);
            if (sphere_visible) {
                EXPECT_NE(r.colour[i], kGreen) << x << "," << y;
                EXPECT_EQ(r.vis.triangle[i], kNoTriangle) << x << "," << y;
                EXPECT_NEAR(r.vis.depth[i], rays.window_depth(cam.eye + d * float(ts)), 2e-5f);
                sphere_wins += on_quad;
            } else if (on_quad) {
                EXPECT_EQ(r.colour[i], kGreen) << x << "," << y;
                EXPECT_NE(r.vis.triangle[i], kNoTriangle) << x << "," << y;
                quad_wins += !std::isinf(ts);  // the quad hides a part of the sphere
            }
        }
    EXPECT_GT(sphere_wins, 30);
    EXPECT_GT(quad_wins, 30);
}

TEST(MarchRaster, FogCoversTrianglesAndMarchedSurfacesAlike) {
    Fog fog;
    fog.density = glm::vec3(0.3f);
    fog.colour = {0.2f, 0.3f, 0.4f};
    const Result clear = render_scene(64, nullptr);
    const Result foggy = render_scene(64, &fog);
    const Camera cam = march_camera(W, H);
    const RayGenerator rays(cam, W, H);
    for (int y = 0; y < H; y += 3)
        for (int x = 0; x < W; x += 3) {
            const size_t i = size_t(y) * W + x;
            const float distance = rays.distance_from_depth(x, y, clear.vis.depth[i]);
            const glm::vec3 expected = fog.apply(glm::vec3(clear.colour[i]), cam.eye, rays.direction(x, y), distance);
            EXPECT_NEAR(foggy.colour[i].x, expected.x, 1e-5f) << x << "," << y;
            EXPECT_NEAR(foggy.colour[i].z, expected.z, 1e-5f) << x << "," << y;
        }
}

TEST(MarchRaster, FrameIsIdenticalForAnyThreadCountAndTileSize) {
    Fog fog;
    fog.density = {0.1f, 0.2f, 0.3f};
    fog.falloff = 0.5f;
    Result one;
    {
        tbb::global_control single(tbb::global_control::max_allowed_parallelism, 1);
        one = render_scene(16, &fog);
    }
    const Result many = render_scene(64, &fog);
    ASSERT_EQ(one.colour.size(), many.colour.size());
    EXPECT_EQ(std::memcmp(one.colour.data(), many.colour.data(), one.colour.size() * sizeof(glm::vec4)), 0);
    EXPECT_EQ(std::memcmp(one.vis.depth.data(), many.vis.depth.data(), one.vis.depth.size() * sizeof(float)), 0);
    EXPECT_EQ(one.vis.triangle, many.vis.triangle);
}
