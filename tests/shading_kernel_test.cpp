// Shading formulas through the whole shading path (bake -> visibility -> FrameShading):
// tangent frames, Gouraud vs Phong, perspective-correct texturing, mip selection in the
// kernel, blending order, normal maps, and the SIMD kernel against its scalar reference.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <random>

#include <glm/gtc/constants.hpp>

#include "procedural/normal_map.h"
#include "raster/geometry/param_surface.h"
#include "raster/geometry/surfaces.h"
#include "raster/shade/tangent_frame.h"
#include "shading_harness.h"

using namespace tessera;

namespace {

using V = simd::V3<float>;
V v3(glm::vec3 a) { return {a.x, a.y, a.z}; }
glm::vec3 g3(V a) { return {a.x, a.y, a.z}; }

// A quad in the z = 0 plane, corners (-1,-1) .. (1,1), uv (0,0) .. (1,1), facing +z; two
// triangles, so its interior has no vertex.
std::shared_ptr<const Mesh> quad(int n = 1) {
    return std::make_shared<const Mesh>(geometry::tessellate(
        [](float u, float v) {
            return geometry::SurfacePoint{{2 * u - 1, 2 * v - 1, 0}, {2, 0, 0}, {0, 2, 0}, {0, 0, 1}};
        },
        n, n));
}

scene::Scene one_object(std::shared_ptr<const Mesh> mesh, scene::Material material) {
    scene::Scene s;
    s.camera.eye = {0, 0, 3};
    s.camera.aspect = 1.0f;
    s.camera.fovy_deg = 60.0f;
    s.materials = {material};
    s.objects = {scene::Object{"object", std::move(mesh), 0, {}, {}}};
    s.lights = {scene::point_light({0, 0, 1.0f}, glm::vec3(0.0f), glm::vec3(1.0f))};
    return s;
}

glm::vec4 checker_texel(glm::vec2 uv, int cells) {
    const int x = int(std::floor(uv.x * float(cells))), y = int(std::floor(uv.y * float(cells)));
    return glm::vec4(glm::vec3(float((x + y) & 1)), 1.0f);
}

}  // namespace

TEST(ShadingTangentFrame, FormulaAgainstHandComputedFrames) {
    // Positions in the xz plane, s along +x, t along -z: S = +x, T = -z (and S x T = +y = N).
    const V p[3] = {v3({0, 0, 0}), v3({2, 0, 0}), v3({0, 0, -2})};
    const float s[3] = {0, 1, 0}, t[3] = {0, 0, 1};
    const auto f = shade::tangent_frame<float>(p, s, t, v3({0, 1, 0}));
    EXPECT_LT(glm::length(g3(f.s) - glm::vec3(1, 0, 0)), 1e-6f);
    EXPECT_LT(glm::length(g3(f.t) - glm::vec3(0, 0, -1)), 1e-6f);
    // The same triangle listed clockwise: the frame does not depend on the corner order.
    const V q[3] = {p[0], p[2], p[1]};
    const float sq[3] = {0, 0, 1}, tq[3] = {0, 1, 0};
    const auto g = shade::tangent_frame<float>(q, sq, tq, v3({0, 1, 0}));
    EXPECT_LT(glm::length(g3(g.s) - glm::vec3(1, 0, 0)), 1e-6f);
    EXPECT_LT(glm::length(g3(g.t) - glm::vec3(0, 0, -1)), 1e-6f);
    // Mirrored uv (s decreasing along +x): S follows +s, i.e. -x.
    const float sm[3] = {0, -1, 0};
    const auto h = shade::tangent_frame<float>(p, sm, t, v3({0, 1, 0}));
    EXPECT_LT(glm::length(g3(h.s) - glm::vec3(-1, 0, 0)), 1e-6f);
    // A skewed layout: T is the in-plane direction of constant s, by the formula
    // tgT = |dS2 * Vec1 - dS1 * Vec2| checked by hand: Vec1 = p3 - p2 = (-2, 0, -2),
    // Vec2 = p1 - p2 = (-2, 0, 0), dS1 = 0.5 - 1 = -0.5, dS2 = 0 - 1 = -1:
    // -1 * (-2, 0, -2) + 0.5 * (-2, 0, 0) = (1, 0, 2) -> (1, 0, 2)/sqrt(5), pointing to +t.
    const float ss[3] = {0, 1, 0.5f};
    const V r[3] = {v3({0, 0, 0}), v3({2, 0, 0}), v3({0, 0, -2})};
    const float ts[3] = {0, 0, 1};
    const auto k = shade::tangent_frame<float>(r, ss, ts, v3({0, 1, 0}));
    const glm::vec3 expected_t = -glm::normalize(glm::vec3(1, 0, 2));  // +t runs towards -z
    EXPECT_LT(glm::length(g3(k.t) - expected_t), 1e-6f);
    EXPECT_NEAR(glm::dot(g3(k.s), g3(k.t)), 0.0f, 1e-6f);
    EXPECT_LT(glm::length(g3(k.s) - glm::normalize(glm::cross(expected_t, glm::vec3(0, 1, 0)))), 1e-6f);
    // Degenerate uv: an orthonormal frame around N, no NaN.
    const float zero[3] = {0, 0, 0};
    const auto d = shade::tangent_frame<float>(p, zero, zero, v3({0, 1, 0}));
    EXPECT_NEAR(glm::length(g3(d.s)), 1.0f, 1e-6f);
    EXPECT_NEAR(glm::dot(g3(d.s), glm::vec3(0, 1, 0)), 0.0f, 1e-6f);
}

TEST(ShadingModels, PhongShowsAHighlightInsideALargeTriangleThatGouraudMisses) {
    scene::Material m;
    m.ka = glm::vec3(0.0f);
    m.kd = glm::vec3(0.2f);
    m.ks = glm::vec3(0.8f);
    m.shine = 64.0f;
    m.model = scene::ShadingModel::phong;
    const Frame phong = test::render_scene(one_object(quad(), m), 64, 64);
    m.model = scene::ShadingModel::gouraud;
    const Frame gouraud = test::render_scene(one_object(quad(), m), 64, 64);
    // The light hovers over the centre: the highlight is there, far from every vertex.
    EXPECT_GT(phong.at(32, 32).r, 0.9f);
    EXPECT_LT(gouraud.at(32, 32).r, 0.3f);
    // Per-vertex colour interpolation: the centre is the mean of the corner colours, so
    // Gouraud is smooth but dull everywhere inside.
    EXPECT_LT(std::abs(gouraud.at(32, 32).r - gouraud.at(20, 32).r), 0.05f);
}

TEST(ShadingModels, ToonHasTwoLevelsAndABlackSilhouette) {
    scene::Material m;
    m.model = scene::ShadingModel::toon;
    m.kd = glm::vec3(0.8f, 0.4f, 0.2f);
    scene::Scene scene = one_object(std::make_shared<const Mesh>(geometry::tessellate(geometry::sphere_surface({0, 0, 0}, 1.0f), 48, 24)), m);
    scene.lights = {scene::directional_light({1, 1, 1}, glm::vec3(0.0f), glm::vec3(1.0f))};
    const Frame f = test::render_scene(scene, 64, 64);
    int full = 0, half = 0, black = 0, other = 0;
    for (int y = 8; y < 56; ++y)
        for (int x = 8; x < 56; ++x) {
            const glm::vec4 c = f.at(x, y);
            if (glm::length(glm::vec3(c) - m.kd) < 1e-5f) ++full;
            else if (glm::length(glm::vec3(c) - 0.5f * m.kd) < 1e-5f) ++half;
            else if (glm::length(glm::vec3(c)) < 1e-6f) ++black;
            else ++other;  // the background
        }
    EXPECT_GT(full, 100);
    EXPECT_GT(half, 100);
    EXPECT_GT(black, 20);
    // On the sphere's rim |N.V| is small: against a white background, the outermost covered
    // pixels of the middle row are black.
    scene.background.colour = glm::vec3(1.0f);
    const Frame g = test::render_scene(scene, 64, 64);
    int x = 0;
    while (x < 64 && g.at(x, 32).r == 1.0f) ++x;
    ASSERT_LT(x, 32);
    EXPECT_EQ(glm::vec3(g.at(x, 32)), glm::vec3(0.0f));
    int r = 63;
    while (r > 0 && g.at(r, 32).r == 1.0f) --r;
    EXPECT_EQ(glm::vec3(g.at(r, 32)), glm::vec3(0.0f));
    (void)other;
}

TEST(ShadingTextures, PerspectiveCorrectCheckerboardOnATiltedPlane) {
    // A 1 x 1 checker of 8 x 8 cells on the quad, tilted away by 60 degrees; lit head-on by a
    // directional light along its normal with kd = 1, no ambient or specular: colour = texel.
    const int cells = 8, size = 128;
    std::vector<glm::vec4> texels(64 * 64);
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x) texels[size_t(y * 64 + x)] = glm::vec4(glm::vec3(float(((x / 8) + (y / 8)) & 1)), 1.0f);
    scene::Material m;
    m.ka = glm::vec3(0.0f);
    m.kd = glm::vec3(1.0f);
    m.ks = glm::vec3(0.0f);
    m.diffuse_texture = 0;
    m.filter = texture::TextureFilter::nearest;
    scene::Scene scene = one_object(quad(), m);
    scene.textures.emplace_back(64, 64, texels);
    const float angle = -glm::radians(60.0f);
    scene.objects[0].transform.axis = {1, 0, 0};
    scene.objects[0].transform.angle = angle;
    scene.objects[0].transform.scale = glm::vec3(1.5f);
    const glm::vec3 normal(0, std::sin(-angle), std::cos(angle));
    scene.lights = {scene::directional_light(normal, glm::vec3(0.0f), glm::vec3(1.0f))};
    const Frame f = test::render_scene(scene, size, size);

    // The analytic answer: intersect each pixel ray with the plane, read the checker there.
    const glm::mat4 inverse = scene.objects[0].transform.inverse();
    int covered = 0, wrong = 0, wrong_affine = 0;
    const scene::BakedScene baked = scene::bake(scene);
    const VisibilityBuffer vis = test::cast_visibility(baked, scene, size, size);
    const glm::mat4 vp = scene.camera.view_projection();
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            const uint32_t tri = vis.triangle[size_t(y * size + x)];
            if (tri == kNoTriangle) continue;
            const glm::vec3 dir = test::pixel_ray(scene.camera, size, size, x, y);
            const glm::vec3 o = glm::vec3(inverse * glm::vec4(scene.camera.eye, 1.0f));
            const glm::vec3 d = glm::vec3(inverse * glm::vec4(dir, 0.0f));
            const glm::vec3 hit = o + d * (-o.z / d.z);
            const glm::vec2 uv((hit.x + 1) / 2, (hit.y + 1) / 2);
            // Stay away from cell edges, where one pixel's rounding decides.
            const glm::vec2 cell = uv * float(cells);
            if (std::abs(cell.x - std::round(cell.x)) < 0.05f || std::abs(cell.y - std::round(cell.y)) < 0.05f) continue;
            ++covered;
            wrong += std::abs(f.at(x, y).r - checker_texel(uv, cells).r) > 0.01f;
            // What screen-space (affine) interpolation would have read: uv linear in window x, y.
            const Mesh& mesh = baked.mesh;
            glm::vec2 w[3];
            for (int k = 0; k < 3; ++k) {
                const glm::vec4 c = vp * glm::vec4(mesh.positions[mesh.indices[3 * tri + k]], 1.0f);
                w[k] = {(c.x / c.w + 1) * size / 2, (1 - c.y / c.w) * size / 2};
            }
            const glm::vec2 px(x + 0.5f, y + 0.5f);
            const float area = (w[1].x - w[0].x) * (w[2].y - w[0].y) - (w[2].x - w[0].x) * (w[1].y - w[0].y);
            const float b1 = ((px.x - w[0].x) * (w[2].y - w[0].y) - (w[2].x - w[0].x) * (px.y - w[0].y)) / area;
            const float b2 = ((w[1].x - w[0].x) * (px.y - w[0].y) - (px.x - w[0].x) * (w[1].y - w[0].y)) / area;
            const glm::vec2 affine = mesh.uvs[mesh.indices[3 * tri]] * (1 - b1 - b2) +
                                     mesh.uvs[mesh.indices[3 * tri + 1]] * b1 + mesh.uvs[mesh.indices[3 * tri + 2]] * b2;
            wrong_affine += std::abs(checker_texel(affine, cells).r - checker_texel(uv, cells).r) > 0.01f;
        }
    ASSERT_GT(covered, 2000);
    EXPECT_EQ(wrong, 0);
    EXPECT_GT(wrong_affine, covered / 20);  // the test can tell the two apart
}

TEST(ShadingTextures, KernelDerivativesSelectTheMipLevel) {
    // The quad seen head-on fills exactly 64 x 64 pixels (fov 90, distance 2, frame 128) and
    // carries a 256 x 256 one-texel checker: 4 texels per pixel, lambda = 2, grey.
    std::vector<glm::vec4> texels(256 * 256);
    for (int y = 0; y < 256; ++y)
        for (int x = 0; x < 256; ++x) texels[size_t(y * 256 + x)] = glm::vec4(glm::vec3(float((x + y) & 1)), 1.0f);
    scene::Material m;
    m.ka = glm::vec3(0.0f);
    m.kd = glm::vec3(1.0f);
    m.ks = glm::vec3(0.0f);
    m.diffuse_texture = 0;
    scene::Scene scene = one_object(quad(), m);
    scene.camera.eye = {0, 0, 2};
    scene.camera.fovy_deg = 90.0f;
    scene.textures.emplace_back(256, 256, texels);
    scene.lights = {scene::directional_light({0, 0, 1}, glm::vec3(0.0f), glm::vec3(1.0f))};
    for (texture::TextureFilter filter : {texture::TextureFilter::trilinear, texture::TextureFilter::mipmap}) {
        scene.materials[0].filter = filter;
        const Frame f = test::render_scene(scene, 128, 128);
        for (int y = 40; y < 88; y += 5)
            for (int x = 40; x < 88; x += 5) EXPECT_NEAR(f.at(x, y).r, 0.5f, 0.02f) << x << "," << y;
    }
    scene.materials[0].filter = texture::TextureFilter::nearest;
    const Frame aliased = test::render_scene(scene, 128, 128);
    int extreme = 0;
    for (int y = 40; y < 88; ++y)
        for (int x = 40; x < 88; ++x) extreme += aliased.at(x, y).r < 0.01f || aliased.at(x, y).r > 0.99f;
    EXPECT_EQ(extreme, 48 * 48);
}

TEST(ShadingTransparency, BlendingFollowsSubmissionOrder) {
    // Two overlapping transparent quads in front of nothing (black background): red then blue.
    // (Pixels are read off the quads' diagonal, where the brute-force harness hits both
    // triangles; the rasterizer's fill rule gives the edge to one.)
    scene::Material red, blue;
    red.model = blue.model = scene::ShadingModel::flat;
    red.ka = blue.ka = glm::vec3(0.0f);
    red.ks = blue.ks = glm::vec3(0.0f);
    red.kd = {1, 0, 0};
    blue.kd = {0, 0, 1};
    red.opacity = blue.opacity = 0.5f;
    scene::Scene scene = one_object(quad(), red);
    scene.materials.push_back(blue);
    scene.objects.push_back(scene::Object{"blue", quad(), 1, {}, {}});
    scene.objects[1].transform.translation = {0, 0, 0.5f};  // nearer, but drawn second
    scene.lights = {scene::directional_light({0, 0, 1}, glm::vec3(0.0f), glm::vec3(1.0f))};
    const Frame f = test::render_scene(scene, 32, 32);
    // c = c_src a + c_dst (1 - a): red over black, then blue over that.
    const glm::vec4 expected = shade::blend_over(shade::blend_over({0, 0, 0, 1}, {1, 0, 0, 0.5f}), {0, 0, 1, 0.5f});
    EXPECT_LT(glm::length(f.at(12, 14) - expected), 1e-5f);
    EXPECT_NEAR(f.at(12, 14).r, 0.25f, 1e-6f);
    EXPECT_NEAR(f.at(12, 14).b, 0.5f, 1e-6f);
    // Swapping the submission order swaps the weights: order matters.
    std::swap(scene.objects[0], scene.objects[1]);
    const Frame g = test::render_scene(scene, 32, 32);
    EXPECT_NEAR(g.at(12, 14).r, 0.5f, 1e-6f);
    EXPECT_NEAR(g.at(12, 14).b, 0.25f, 1e-6f);
}

TEST(ShadingNormalMaps, FlatMapKeepsTheGeometricNormal) {
    // The normal map of a flat height field (procedural/normal_map.h: (0, 0, 1) everywhere,
    // (128, 128, 255) in 8 bits) must not change the shading.
    const procedural::NormalMap flat = procedural::normal_map(procedural::Grid(16, 8, 0.3f), 8.0f,
                                                              procedural::Boundary::periodic);
    io::FloatImage encoded;
    encoded.width = flat.width;
    encoded.height = flat.height;
    encoded.channels = 3;
    for (float c : flat.xyz) encoded.pixels.push_back(c * 0.5f + 0.5f);
    scene::Material m;
    m.kd = {0.7f, 0.5f, 0.3f};
    scene::Scene plain = one_object(std::make_shared<const Mesh>(geometry::tessellate(geometry::sphere_surface({0, 0, 0}, 1.0f), 32, 16)), m);
    plain.lights = {scene::point_light({2, 2, 3}, glm::vec3(0.1f), glm::vec3(1.0f))};
    scene::Scene mapped = plain;
    mapped.textures.push_back(texture::Texture::from_image(encoded, texture::TexelEncoding::linear));
    mapped.materials[0].normal_texture = 0;
    const Frame a = test::render_scene(plain, 64, 64), b = test::render_scene(mapped, 64, 64);
    float worst = 0.0f;
    for (size_t i = 0; i < a.pixels.size(); ++i) worst = std::max(worst, glm::length(a.pixels[i] - b.pixels[i]));
    EXPECT_LT(worst, 1e-4f);
    // And a tilted map does change it (the test can fail).
    mapped.textures[0] = texture::Texture(1, 1, {glm::vec4(0.9f, 0.5f, 0.8f, 1.0f)});
    const Frame c = test::render_scene(mapped, 64, 64);
    EXPECT_GT(glm::length(c.at(32, 32) - a.at(32, 32)), 0.02f);
}

TEST(ShadingKernel, SimdMatchesTheScalarReference) {
    // Every model, textured and normal-mapped, several lights: all visible pixels both ways.
    scene::Scene scene;
    scene.camera.eye = {0, 0.5f, 4};
    scene.camera.aspect = 1.0f;
    std::vector<glm::vec4> texels(32 * 16);
    for (size_t i = 0; i < texels.size(); ++i) texels[i] = glm::vec4(float(i % 7) / 7, float(i % 5) / 5, 0.5f, 1);
    scene.textures.emplace_back(32, 16, texels);
    scene.textures.emplace_back(8, 8, std::vector<glm::vec4>(64, glm::vec4(0.6f, 0.4f, 0.9f, 1.0f)));
    for (scene::ShadingModel model : {scene::ShadingModel::flat, scene::ShadingModel::gouraud, scene::ShadingModel::phong, scene::ShadingModel::toon}) {
        scene::Material m;
        m.model = model;
        scene.materials.push_back(m);
        m.diffuse_texture = 0;
        m.normal_texture = 1;
        scene.materials.push_back(m);
    }
    const auto sphere = std::make_shared<const Mesh>(geometry::tessellate(geometry::sphere_surface({0, 0, 0}, 0.5f), 24, 12));
    for (uint32_t i = 0; i < scene.materials.size(); ++i) {
        scene::Object o{"s", sphere, i, {}, {}};
        o.transform.translation = {float(i % 4) - 1.5f, float(i / 4) - 0.5f, 0.0f};
        scene.objects.push_back(o);
    }
    scene.lights = {scene::point_light({2, 2, 3}, glm::vec3(0.1f), glm::vec3(0.8f)),
                    scene::directional_light({-1, 0.5f, 1}, glm::vec3(0.05f), glm::vec3(0.5f, 0.5f, 0.6f))};
    const scene::BakedScene baked = scene::bake(scene);
    const VisibilityBuffer vis = test::cast_visibility(baked, scene, 96, 96);
    const shade::FrameShading shading(baked, scene, shade::RenderState{scene.camera, 96, 96, scene.lights});
    std::vector<shade::CoveredPixel> pixels;
    for (int y = 0; y < 96; ++y)
        for (int x = 0; x < 96; ++x)
            if (vis.triangle[size_t(y * 96 + x)] != kNoTriangle) pixels.push_back({x, y, vis.triangle[size_t(y * 96 + x)]});
    ASSERT_GT(pixels.size(), 2000u);
    std::vector<glm::vec4> fast(pixels.size()), reference(pixels.size());
    shading.shade(pixels, fast);
    shading.shade_reference(pixels, reference);
    float worst = 0.0f;
    for (size_t i = 0; i < pixels.size(); ++i) worst = std::max(worst, glm::length(fast[i] - reference[i]));
    EXPECT_LT(worst, 1e-5f);

    // A pixel's colour does not depend on the pixels it shares lanes with: in scan order most
    // lane groups lie on one triangle (its attributes broadcast), shuffled almost none do
    // (filled lane by lane); the two give the same bits.
    std::vector<size_t> permutation(pixels.size());
    for (size_t i = 0; i < permutation.size(); ++i) permutation[i] = i;
    std::shuffle(permutation.begin(), permutation.end(), std::mt19937(9));
    std::vector<shade::CoveredPixel> shuffled(pixels.size());
    for (size_t i = 0; i < pixels.size(); ++i) shuffled[i] = pixels[permutation[i]];
    std::vector<glm::vec4> shuffled_out(pixels.size());
    shading.shade(shuffled, shuffled_out);
    for (size_t i = 0; i < pixels.size(); ++i)
        ASSERT_EQ(0, std::memcmp(&shuffled_out[i], &fast[permutation[i]], sizeof(glm::vec4))) << i;

    // The row-wise opaque pass equals the pixel list through shade(), bit for bit, on whole
    // tiles and on tiles cut mid-group (mixed materials and background in one lane group).
    for (const TileRect rect : {TileRect{0, 0, 96, 96}, TileRect{5, 3, 64, 70}, TileRect{37, 41, 96, 96}}) {
        std::vector<glm::vec4> rows(96 * 96, glm::vec4(-1.0f)), list(96 * 96, glm::vec4(-1.0f));
        VisibilityBuffer v = vis;
        shade::shade_surfaces(shading, frame_tile(v, rows.data(), rect));
        shade::shade_surfaces_reference(shading, frame_tile(v, list.data(), rect));
        ASSERT_EQ(0, std::memcmp(rows.data(), list.data(), rows.size() * sizeof(glm::vec4)));
    }
}

TEST(ShadingKernel, DegenerateInputsGiveFiniteColours) {
    // Zero-length normals, a triangle collapsed to a point, NaN texture coordinates, a 1x1
    // texture and a triangle id out of range: every output is finite, nothing crashes.
    auto mesh = std::make_shared<Mesh>(*quad());
    for (glm::vec3& n : mesh->normals) n = glm::vec3(0.0f);
    mesh->uvs[0] = glm::vec2(NAN, INFINITY);
    mesh->positions.push_back({0.2f, 0.2f, 0.0f});
    mesh->normals.push_back(glm::vec3(0.0f));
    mesh->uvs.push_back(glm::vec2(0.5f));
    mesh->tangents.push_back(glm::vec4(1, 0, 0, 1));
    const uint32_t p = uint32_t(mesh->positions.size() - 1);
    mesh->indices.insert(mesh->indices.end(), {p, p, p});
    scene::Material m;
    m.diffuse_texture = 0;
    m.normal_texture = 0;
    scene::Scene scene = one_object(mesh, m);
    scene.textures.emplace_back(1, 1, std::vector<glm::vec4>{glm::vec4(0.5f, 0.5f, 1.0f, 1.0f)});
    const scene::BakedScene baked = scene::bake(scene);
    const shade::FrameShading shading(baked, scene, shade::RenderState{scene.camera, 32, 32, scene.lights});
    std::vector<shade::CoveredPixel> pixels;
    for (uint32_t t = 0; t < 4; ++t)
        for (int x = 0; x < 32; x += 3) pixels.push_back({x, 16, t == 3 ? 12345u : t});
    std::vector<glm::vec4> out(pixels.size()), ref(pixels.size());
    shading.shade(pixels, out);
    shading.shade_reference(pixels, ref);
    for (size_t i = 0; i < out.size(); ++i)
        for (int c = 0; c < 4; ++c) {
            EXPECT_TRUE(std::isfinite(out[i][c])) << i;
            EXPECT_TRUE(std::isfinite(ref[i][c])) << i;
        }
    // Without normals, the quad's pixels are lit with its face normal (facing the light).
    EXPECT_GT(out[12].r, 0.1f);
}
