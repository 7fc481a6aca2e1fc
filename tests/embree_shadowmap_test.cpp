// Shadow maps rendered by the rasterizer, against the same questions the shadow rays answer:
// occluded and lit points, no acne on a plane with the default bias, agreement with Embree's
// exact shadows on the sphere grid, determinism, broken triangles, bad options.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <bit>
#include <cstring>
#include <limits>
#include <vector>

#include "procedural/hash.h"
#include "raster/core/pixel_rays.h"
#include "raster/embree/scene.h"
#include "raster/embree/shadow_rays.h"
#include "raster/pipeline/rasterizer.h"
#include "raster/shadow/mask_compare.h"
#include "raster/shadow/shadow_edges.h"
#include "raster/shadow/shadow_map.h"
#include "raster/workloads/sphere_grid.h"

namespace tessera::shadow {
namespace {

const glm::vec3 kUp{0.0f, 1.0f, 0.0f};

// The 20,000-triangle sphere grid rasterized at w x h: the frame several tests below read.
struct RasterizedGrid {
    workloads::SphereGridScene grid = workloads::make_sphere_grid(20000);
    glm::mat4 vp = grid.camera.view_projection();
    pipeline::Rasterizer rasterizer;
    VisibilityBuffer vis;
    RasterizedGrid(int w, int h) {
        rasterizer.render(grid.mesh, vp, pipeline::Viewport(w, h), pipeline::RasterOptions{}, vis);
    }
};

Mesh ground_and_occluder() {
    Mesh mesh;
    workloads::append_ground(mesh, 0.0f, 0.0f, 0.0f, 10.0f, 4);
    workloads::append_ground(mesh, 0.0f, 0.0f, 1.0f, 1.0f, 1);
    embree::reserve_ray_padding(mesh);
    return mesh;
}

TEST(ShadowMap, PointUnderOccluderIsShadowedAndBesideItLit) {
    const Mesh mesh = ground_and_occluder();
    pipeline::Rasterizer rasterizer;
    for (int pcf : {0, 1, 2}) {
        ShadowMapOptions options;
        options.resolution = 512;
        options.pcf_radius = pcf;
        const ShadowMap map(rasterizer, mesh, {0.0f, 5.0f, 0.0f}, options);
        EXPECT_FALSE(map.lit({0.0f, 0.0f, 0.0f}, kUp)) << "pcf " << pcf;
        EXPECT_FALSE(map.lit({0.3f, 0.0f, -0.3f}, kUp)) << "pcf " << pcf;
        EXPECT_TRUE(map.lit({2.0f, 0.0f, 0.0f}, kUp)) << "pcf " << pcf;
        EXPECT_TRUE(map.lit({0.2f, 1.0f, 0.2f}, kUp)) << "the occluder's own top, pcf " << pcf;
    }
}

// Every covered pixel of a lone plane must be lit, for steep and low lights alike.
TEST(ShadowMap, FlatPlaneHasNoAcneWithTheDefaultBias) {
    Mesh mesh;
    workloads::append_ground(mesh, 0.0f, 0.0f, 0.0f, 40.0f, 16);
    embree::reserve_ray_padding(mesh);
    Camera camera;
    camera.eye = {0.0f, 6.0f, 14.0f};
    camera.lookat = {0.0f, 0.0f, 0.0f};
    const glm::mat4 vp = camera.view_projection();
    pipeline::Rasterizer rasterizer;
    VisibilityBuffer vis;
    rasterizer.render(mesh, vp, pipeline::Viewport(320, 180), pipeline::RasterOptions{}, vis);
    // Elevations of about 70, 30 and 10 degrees above the plane's centre, from three sides.
    const std::vector<glm::vec3> lights = {{5.0f, 30.0f, 5.0f}, {-35.0f, 20.0f, 0.0f},
                                           {0.0f, 10.0f, -57.0f}};
    for (int resolution : {256, 2048}) {
        ShadowMapOptions options;
        options.resolution = resolution;
        std::vector<ShadowMap> maps;
        for (const glm::vec3& light : lights) maps.emplace_back(rasterizer, mesh, light, options);
        const LightMask mask = compute_light_mask(vis, mesh, vp, lights, shadow_map_test(maps));
        size_t covered = 0, acne = 0;
        for (size_t p = 0; p < mask.bits.size(); ++p) {
            if (vis.triangle[p] == kNoTriangle) continue;
            ++covered;
            acne += mask.bits[p] != 7;
        }
        EXPECT_GT(covered, mask.bits.size() / 3);
        EXPECT_EQ(acne, 0u) << "resolution " << resolution;
    }
}

TEST(ShadowMap, WithoutBiasThePlaneHasAcne) {
    // The previous test can fail: with no bias a low light self-shadows the plane.
    Mesh mesh;
    workloads::append_ground(mesh, 0.0f, 0.0f, 0.0f, 40.0f, 16);
    Camera camera;
    camera.eye = {0.0f, 6.0f, 14.0f};
    const glm::mat4 vp = camera.view_projection();
    pipeline::Rasterizer rasterizer;
    VisibilityBuffer vis;
    rasterizer.render(mesh, vp, pipeline::Viewport(320, 180), pipeline::RasterOptions{}, vis);
    const std::vector<glm::vec3> lights = {{0.0f, 10.0f, -57.0f}};
    ShadowMapOptions options;
    options.resolution = 256;
    options.normal_offset = 0.0f;
    options.depth_bias = 0.0f;
    const std::vector<ShadowMap> maps = {ShadowMap(rasterizer, mesh, lights[0], options)};
    const LightMask mask = compute_light_mask(vis, mesh, vp, lights, shadow_map_test(maps));
    size_t dark = 0;
    for (size_t p = 0; p < mask.bits.size(); ++p)
        dark += vis.triangle[p] != kNoTriangle && mask.bits[p] == 0;
    EXPECT_GT(dark, 100u);
}

TEST(ShadowMap, AgreesWithEmbreeShadowRaysOnTheSphereGrid) {
    RasterizedGrid frame(640, 360);
    auto& [grid, vp, rasterizer, vis] = frame;
    const std::vector<glm::vec3> lights = {grid.light};
    const std::vector<ShadowMap> maps = {ShadowMap(rasterizer, grid.mesh, grid.light)};
    const LightMask by_map = compute_light_mask(vis, grid.mesh, vp, lights, shadow_map_test(maps));
    const embree::RayScene scene(embree::default_ray_device(), grid.mesh);
    const LightMask by_rays =
        compute_light_mask(vis, grid.mesh, vp, lights, embree::shadow_ray_test(scene));
    const LightMask grazing = compute_light_mask(vis, grid.mesh, vp, lights, grazing_lights(0.1f));
    const MaskAgreement agreement = compare_light_masks(by_map, by_rays, vis, &grazing);
    EXPECT_GT(agreement.compared, 100000u);
    EXPECT_GE(agreement.agreement(), 0.99);
    size_t shadowed = 0;
    for (size_t p = 0; p < vis.triangle.size(); ++p)
        shadowed += vis.triangle[p] != kNoTriangle && by_rays.bits[p] == 0;
    EXPECT_GT(shadowed, 10000u) << "a comparison without shadows proves nothing";
}

TEST(ShadowMap, MaskIsTheSameForAnyThreadCount) {
    const workloads::SphereGridScene grid = workloads::make_sphere_grid(5000);
    const glm::mat4 vp = grid.camera.view_projection();
    const std::vector<glm::vec3> lights = {grid.light, {-4.0f, 6.0f, 2.0f}};
    const auto render = [&] {
        pipeline::Rasterizer rasterizer;
        VisibilityBuffer vis;
        rasterizer.render(grid.mesh, vp, pipeline::Viewport(333, 187), pipeline::RasterOptions{}, vis);
        ShadowMapOptions options;
        options.resolution = 700;
        std::vector<ShadowMap> maps;
        for (const glm::vec3& light : lights) maps.emplace_back(rasterizer, grid.mesh, light, options);
        return compute_light_mask(vis, grid.mesh, vp, lights, shadow_map_test(maps)).bits;
    };
    const auto all = render();
    const tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
    EXPECT_EQ(render(), all);
}

TEST(ShadowMap, BrokenTrianglesAreSkippedAndTheFrameStillRenders) {
    Mesh mesh = ground_and_occluder();
    const float nan = std::numeric_limits<float>::quiet_NaN();
    mesh.positions.push_back({nan, 3.0f, 0.0f});
    mesh.positions.push_back({std::numeric_limits<float>::infinity(), 3.0f, 0.0f});
    const auto last = uint32_t(mesh.positions.size());
    mesh.indices.insert(mesh.indices.end(), {0, last - 2, 1, 0, last - 1, 1, 0, 1, 999});
    embree::reserve_ray_padding(mesh);
    pipeline::Rasterizer rasterizer;
    ShadowMapOptions options;
    options.resolution = 256;
    const ShadowMap map(rasterizer, mesh, {0.0f, 5.0f, 0.0f}, options);
    EXPECT_FALSE(map.lit({0.0f, 0.0f, 0.0f}, kUp));
    EXPECT_TRUE(map.lit({2.0f, 0.0f, 0.0f}, kUp));
    const embree::RayScene scene(embree::default_ray_device(), mesh);
    EXPECT_EQ(scene.defects().total(), 3u);
}

// The SIMD lookup (mark_lit) must answer exactly what lit() answers point by point: on every
// surface point of a sphere-grid frame, and on random points and normals around the scene
// (outside the map, behind the light, on its edges), for several PCF radii and map sizes.
TEST(ShadowMap, SimdLookupEqualsScalarReference) {
    const int w = 320, h = 180;
    RasterizedGrid frame(w, h);
    auto& [grid, vp, rasterizer, vis] = frame;
    SurfacePoints points;
    gather_surface_points(vis, grid.mesh, PixelRays(vp, w, h), TileRect{0, 0, w, h}, points);
    const size_t from_frame = points.size();
    ASSERT_GT(from_frame, 20000u);
    procedural::SplitMix64 random(6);
    const auto uniform = [&](float lo, float hi) {
        return lo + (hi - lo) * float(random.next() >> 40) / float(1 << 24);
    };
    const float e = float(grid.grid);
    for (int i = 0; i < 5003; ++i) {  // not a multiple of the lane count
        points.pixel.push_back(0);
        points.position.push_back({uniform(-e, e), uniform(-1.0f, 2.5f * e), uniform(-e, e)});
        points.normal.push_back(glm::normalize(
            glm::vec3(uniform(-1.0f, 1.0f), uniform(-1.0f, 1.0f), uniform(-1.0f, 1.0f)) + 1e-3f));
    }
    for (int pcf : {0, 1, 2}) {
        for (int resolution : {97, 2048}) {
            ShadowMapOptions options;
            options.resolution = resolution;
            options.pcf_radius = pcf;
            const ShadowMap map(rasterizer, grid.mesh, grid.light, options);
            std::vector<uint8_t> simd(points.size(), 0), scalar(points.size(), 0);
            map.mark_lit(points, 4, simd);
            map.mark_lit_reference(points, 4, scalar);
            size_t lit = 0, differ = 0;
            for (size_t i = 0; i < points.size(); ++i) {
                lit += scalar[i] != 0;
                differ += simd[i] != scalar[i];
            }
            EXPECT_EQ(differ, 0u) << "pcf " << pcf << ", resolution " << resolution;
            EXPECT_GT(lit, points.size() / 4) << "pcf " << pcf << ", resolution " << resolution;
            EXPECT_LT(lit, points.size() - points.size() / 10) << "some points must be dark";
        }
    }
}

// The surface points gathered in lanes are the reference's, bit for bit, and their facing bits
// are faces_light's: on a sphere-grid frame, in tiles cut at odd places (blocks cut by the
// tile's edge), with lights above, beside and below the scene; and the batched pixel rays
// equal ray() one by one.
TEST(SurfacePoints, LanesEqualTheReferenceAndFacingBitsTheTest) {
    const int w = 203, h = 117;
    RasterizedGrid frame(w, h);
    auto& [grid, vp, rasterizer, vis] = frame;
    const PixelRays rays(vp, w, h);
    const glm::vec3 lights[] = {grid.light, {-40.0f, 3.0f, 10.0f}, {5.0f, -30.0f, 0.0f}};
    size_t points_seen = 0;
    for (const TileRect rect : {TileRect{0, 0, w, h}, TileRect{3, 5, 70, 66}, TileRect{150, 100, 203, 117}}) {
        Tile tile;
        tile.rect = rect;
        tile.triangle = vis.triangle.data() + size_t(rect.y0) * size_t(w) + size_t(rect.x0);
        tile.stride = size_t(w);
        SurfacePoints lanes, reference;
        gather_surface_points(tile, size_t(w), grid.mesh, rays, lanes, lights);
        gather_surface_points_reference(tile, size_t(w), grid.mesh, rays, reference);
        ASSERT_EQ(lanes.pixel, reference.pixel);
        ASSERT_EQ(lanes.size(), reference.size());
        ASSERT_EQ(lanes.facing.size(), reference.size());
        for (size_t i = 0; i < lanes.size(); ++i) {
            ASSERT_EQ(0, std::memcmp(&lanes.position[i], &reference.position[i], sizeof(glm::vec3))) << i;
            ASSERT_EQ(0, std::memcmp(&lanes.normal[i], &reference.normal[i], sizeof(glm::vec3))) << i;
            uint8_t facing = 0;
            for (size_t l = 0; l < 3; ++l)
                facing |= uint8_t(faces_light(reference.position[i], reference.normal[i], lights[l]) << l);
            ASSERT_EQ(lanes.facing[i], facing) << i;
        }
        points_seen += lanes.size();
    }
    EXPECT_GT(points_seen, 10000u);
    // PixelRays::rays against ray(), including centres off the pixel grid.
    std::vector<float> x, y;
    for (int i = 0; i < 1000; ++i) {
        x.push_back(float(i % w) + 0.5f + 0.37f * float(i % 3));
        y.push_back(float(i % h) + 0.5f - 0.21f * float(i % 5));
    }
    std::vector<float> o[3], d[3];
    for (int c = 0; c < 3; ++c) o[c].resize(x.size()), d[c].resize(x.size());
    rays.rays(x.size(), x.data(), y.data(), {o[0].data(), o[1].data(), o[2].data(), d[0].data(), d[1].data(), d[2].data()});
    for (size_t i = 0; i < x.size(); ++i) {
        glm::vec3 origin, direction;
        rays.ray(x[i], y[i], origin, direction);
        for (int c = 0; c < 3; ++c) {
            ASSERT_EQ(std::bit_cast<uint32_t>(o[c][i]), std::bit_cast<uint32_t>(origin[c])) << i;
            ASSERT_EQ(std::bit_cast<uint32_t>(d[c][i]), std::bit_cast<uint32_t>(direction[c])) << i;
        }
    }
}

// The points of listed pixels moved off their centres are the reference's points for a tile
// whose centroids all lie there, bit for bit, with the facing bits faces_light gives.
TEST(SurfacePoints, PointsAtAnOffsetAreTheReferenceThroughThatCentroid) {
    const int w = 96, h = 64;
    RasterizedGrid frame(w, h);
    auto& [grid, vp, rasterizer, vis] = frame;
    const PixelRays rays(vp, w, h);
    const glm::vec3 lights[] = {grid.light, {-40.0f, 3.0f, 10.0f}};
    const glm::vec2 at{0.375f, -0.125f};  // a 4x sample position
    std::vector<glm::vec2> centroid(size_t(w) * h, at);
    Tile tile;
    tile.rect = TileRect{0, 0, w, h};
    tile.triangle = vis.triangle.data();
    tile.stride = size_t(w);
    tile.centroid = centroid.data();
    SurfacePoints reference, listed;
    gather_surface_points_reference(tile, size_t(w), grid.mesh, rays, reference);
    ASSERT_GT(reference.size(), 1000u);
    gather_surface_points_at(tile, size_t(w), grid.mesh, rays, reference.pixel, at, listed, lights);
    ASSERT_EQ(listed.pixel, reference.pixel);
    ASSERT_EQ(listed.facing.size(), listed.size());
    for (size_t i = 0; i < listed.size(); ++i) {
        ASSERT_EQ(0, std::memcmp(&listed.position[i], &reference.position[i], sizeof(glm::vec3))) << i;
        ASSERT_EQ(0, std::memcmp(&listed.normal[i], &reference.normal[i], sizeof(glm::vec3))) << i;
        uint8_t facing = 0;
        for (size_t l = 0; l < 2; ++l) facing |= uint8_t(faces_light(listed.position[i], listed.normal[i], lights[l]) << l);
        ASSERT_EQ(listed.facing[i], facing) << i;
    }
    // The lanes gather through the same centroids (its one-lane-at-a-time branch) gives the
    // same points.
    SurfacePoints lanes;
    gather_surface_points(tile, size_t(w), grid.mesh, rays, lanes, lights);
    ASSERT_EQ(lanes.pixel, reference.pixel);
    ASSERT_EQ(lanes.facing.size(), lanes.size());
    for (size_t i = 0; i < lanes.size(); ++i) {
        ASSERT_EQ(0, std::memcmp(&lanes.position[i], &reference.position[i], sizeof(glm::vec3))) << i;
        ASSERT_EQ(0, std::memcmp(&lanes.normal[i], &reference.normal[i], sizeof(glm::vec3))) << i;
        ASSERT_EQ(lanes.facing[i], listed.facing[i]) << i;
    }
}

// find_shadow_edges picks the wholly covered pixels next to another set of lights, and the
// tile's border, and nothing else.
TEST(ShadowEdges, NeighboursWithOtherLightsAndTheBorder) {
    const int w = 6, h = 5, x0 = 10, y0 = 20, image_width = 40;
    std::vector<uint8_t> coverage(size_t(w) * h, 4);
    coverage[size_t(2) * w + 3] = 3;  // pixel (13, 22): partly covered
    Tile tile;
    tile.rect = TileRect{x0, y0, x0 + w, y0 + h};
    tile.stride = size_t(w);
    tile.coverage = coverage.data();
    SurfacePoints points;
    std::vector<uint8_t> lights;
    for (int y = y0; y < y0 + h; ++y)
        for (int x = x0; x < x0 + w; ++x) {
            if (x == 14 && y == 23) continue;  // no point: never a neighbour that differs
            points.pixel.push_back(uint32_t(y * image_width + x));
            lights.push_back(x < 13 ? 1 : 0);  // a boundary between columns 12 and 13
        }
    std::vector<uint16_t> scratch;
    std::vector<uint32_t> edges;
    find_shadow_edges(tile, image_width, points, lights, 4, scratch, edges);
    std::vector<std::pair<int, int>> chosen;
    for (const uint32_t i : edges)
        chosen.push_back({int(points.pixel[i] % image_width), int(points.pixel[i] / image_width)});
    std::vector<std::pair<int, int>> expected;
    for (int y = y0; y < y0 + h; ++y)
        for (int x = x0; x < x0 + w; ++x) {
            const bool border = x == x0 || y == y0 || x == x0 + w - 1 || y == y0 + h - 1;
            const bool boundary = x == 12 || x == 13;
            if ((x == 14 && y == 23) || (x == 13 && y == 22)) continue;
            if (border || boundary) expected.push_back({x, y});
        }
    EXPECT_EQ(chosen, expected);
}

TEST(ShadowMap, BadOptionsAreRejected) {
    const Mesh mesh = ground_and_occluder();
    pipeline::Rasterizer rasterizer;
    for (auto change : {+[](ShadowMapOptions& o) { o.resolution = 8; },
                        +[](ShadowMapOptions& o) { o.resolution = 100000; },
                        +[](ShadowMapOptions& o) { o.pcf_radius = -1; },
                        +[](ShadowMapOptions& o) { o.normal_offset = -1.0f; },
                        +[](ShadowMapOptions& o) { o.depth_bias = std::numeric_limits<float>::quiet_NaN(); }}) {
        ShadowMapOptions options;
        change(options);
        EXPECT_THROW(ShadowMap(rasterizer, mesh, {0.0f, 5.0f, 0.0f}, options), std::invalid_argument);
    }
}

}  // namespace
}  // namespace tessera::shadow
