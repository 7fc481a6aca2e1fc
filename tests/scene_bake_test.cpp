// Transforms (S * R * T and its inverse) and baking objects into one world mesh.
#include <gtest/gtest.h>

#include <glm/gtc/constants.hpp>

#include <tbb/global_control.h>

#include <cstring>

#include "raster/geometry/param_surface.h"
#include "raster/geometry/surfaces.h"
#include "raster/scene/scene.h"

using namespace tessera;

TEST(SceneTransform, OrderScaleRotateTranslateAndInverse) {
    scene::Transform t;
    t.scale = {2.0f, 1.0f, 1.0f};
    t.axis = {0, 0, 1};
    t.angle = glm::half_pi<float>();
    t.translation = {10, 0, 0};
    // (1, 0, 0): scaled to (2, 0, 0), rotated to (0, 2, 0), moved to (10, 2, 0).
    const glm::vec4 p = t.model() * glm::vec4(1, 0, 0, 1);
    EXPECT_LT(glm::length(glm::vec3(p) - glm::vec3(10, 2, 0)), 1e-5f);
    const glm::mat4 identity = t.model() * t.inverse();
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) EXPECT_NEAR(identity[c][r], c == r ? 1.0f : 0.0f, 1e-5f);
    t.scale = {1, 0, 1};
    EXPECT_THROW(t.model(), std::invalid_argument);
}

TEST(SceneTransform, NormalsStayPerpendicularUnderNonUniformScale) {
    scene::Transform t;
    t.scale = {3.0f, 0.5f, 1.0f};
    t.axis = {1, 1, 0};
    t.angle = 0.7f;
    const glm::vec3 tangent(1, -1, 0), normal(1, 1, 0);  // perpendicular in model space
    const glm::vec3 tw = glm::mat3(t.model()) * tangent;
    const glm::vec3 nw = t.normal_matrix() * normal;
    EXPECT_NEAR(glm::dot(tw, nw), 0.0f, 1e-5f);
    EXPECT_GT(std::abs(glm::dot(tw, glm::mat3(t.model()) * normal)), 0.1f);  // the naive way fails
}

namespace {

scene::Scene two_objects() {
    scene::Scene scene;
    scene.materials = {scene::Material{}, scene::Material{}};
    scene.materials[1].model = scene::ShadingModel::toon;
    auto sphere = std::make_shared<const Mesh>(geometry::tessellate(geometry::sphere_surface({0, 0, 0}, 1.0f), 8, 4));
    scene::Object a{"a", sphere, 0, {}, {}};
    scene::Object b{"b", sphere, 1, {}, {}};
    b.transform.translation = {5, 0, 0};
    b.transform.scale = {-1, 1, 1};  // a mirror
    scene.objects = {a, b};
    return scene;
}

}  // namespace

TEST(SceneBake, ConcatenatesInOrderWithMaterialsAndMirroredWinding) {
    const scene::Scene scene = two_objects();
    const scene::BakedScene baked = scene::bake(scene);
    const size_t nv = scene.objects[0].geometry->vertex_count(), nt = scene.objects[0].geometry->triangle_count();
    ASSERT_EQ(baked.mesh.vertex_count(), 2 * nv);
    ASSERT_EQ(baked.mesh.triangle_count(), 2 * nt);
    EXPECT_EQ(baked.triangle_material[0], 0u);
    EXPECT_EQ(baked.triangle_material[nt], 1u);
    EXPECT_EQ(baked.vertex_material[nv], 1u);
    EXPECT_LT(glm::length(baked.mesh.positions[nv + 3] -
                          (glm::vec3(-1, 1, 1) * scene.objects[0].geometry->positions[3] + glm::vec3(5, 0, 0))),
              1e-5f);
    // Both copies stay counter-clockwise around their outward normals.
    for (size_t t = 0; t < baked.mesh.triangle_count(); ++t) {
        const auto& m = baked.mesh;
        const glm::vec3 a = m.positions[m.indices[3 * t]], b = m.positions[m.indices[3 * t + 1]],
                        c = m.positions[m.indices[3 * t + 2]];
        const glm::vec3 face = glm::cross(b - a, c - a);
        if (glm::length(face) < 1e-6f) continue;
        EXPECT_GT(glm::dot(face, m.normals[m.indices[3 * t]] + m.normals[m.indices[3 * t + 1]] +
                                     m.normals[m.indices[3 * t + 2]]),
                  0.0f)
            << "triangle " << t;
    }
}

TEST(SceneBake, SameBytesWhateverTheThreadCount) {
    const scene::Scene scene = two_objects();
    scene::BakedScene one;
    {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
        one = scene::bake(scene);
    }
    const scene::BakedScene many = scene::bake(scene);
    EXPECT_EQ(one.mesh.positions, many.mesh.positions);
    EXPECT_EQ(one.mesh.normals, many.mesh.normals);
    EXPECT_EQ(one.mesh.indices, many.mesh.indices);
}

TEST(SceneBake, BadReferencesAreClearErrors) {
    scene::Scene scene = two_objects();
    scene.objects[1].material = 7;
    EXPECT_THROW(scene::bake(scene), std::invalid_argument);
    scene = two_objects();
    scene.objects[0].geometry = nullptr;
    EXPECT_THROW(scene::bake(scene), std::invalid_argument);
    scene = two_objects();
    scene.materials[0].diffuse_texture = 3;
    EXPECT_THROW(scene::bake(scene), std::invalid_argument);
}

namespace {

// Bit-for-bit equality of two bakes (positions, normals, uvs, tangents, indices, materials
// and parts).
void expect_same_bake(const scene::BakedScene& got, const scene::BakedScene& want, int step) {
    const auto bytes_equal = [](const auto& a, const auto& b) {
        return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(a[0])) == 0);
    };
    EXPECT_TRUE(bytes_equal(got.mesh.positions, want.mesh.positions)) << "step " << step;
    EXPECT_TRUE(bytes_equal(got.mesh.normals, want.mesh.normals)) << "step " << step;
    EXPECT_TRUE(bytes_equal(got.mesh.uvs, want.mesh.uvs)) << "step " << step;
    EXPECT_TRUE(bytes_equal(got.mesh.tangents, want.mesh.tangents)) << "step " << step;
    EXPECT_EQ(got.mesh.indices, want.mesh.indices) << "step " << step;
    EXPECT_EQ(got.triangle_material, want.triangle_material) << "step " << step;
    EXPECT_EQ(got.vertex_material, want.vertex_material) << "step " << step;
    ASSERT_EQ(got.objects.size(), want.objects.size()) << "step " << step;
    for (size_t i = 0; i < got.objects.size(); ++i) {
        EXPECT_EQ(got.objects[i].first_vertex, want.objects[i].first_vertex) << "step " << step;
        EXPECT_EQ(got.objects[i].first_triangle, want.objects[i].first_triangle) << "step " << step;
        EXPECT_EQ(got.objects[i].still, want.objects[i].still) << "step " << step;
    }
}

}  // namespace

TEST(SceneBake, BakerKeepsWhatDidNotChangeAndEqualsAFreshBake) {
    // Frame after frame, one change at a time: the baker's result must equal bake() of the
    // same scene, and it must rewrite only the objects that changed.
    scene::Scene scene = two_objects();
    const auto ball = std::make_shared<const Mesh>(geometry::tessellate(geometry::sphere_surface({0, 0, 0}, 0.5f), 8, 4));
    // The same vertex count as `ball`, without normals or uvs (the other objects have them):
    // put in a slot that had them, its range must read zeros, not what the slot held.
    Mesh bare = *ball;
    bare.normals.clear();
    bare.uvs.clear();
    const auto bare_ball = std::make_shared<const Mesh>(bare);
    scene.objects.push_back({"c", ball, 0, {}, {}});
    scene.objects.back().transform.translation = {0, 3, 0};
    scene.objects[0].animate = [](scene::Object&, float) {};  // marks it as moving (MeshPart::still)
    scene::SceneBaker baker;
    const auto check = [&](int step, size_t rebaked) {
        const scene::BakedScene& got = baker.bake(scene);
        expect_same_bake(got, scene::bake(scene), step);
        EXPECT_EQ(baker.objects_baked(), rebaked) << "step " << step;
    };
    check(0, 3);
    check(1, 0);                                         // nothing changed
    scene.objects[0].transform.translation.x = 1.0f;     // a move
    check(2, 1);
    scene.objects[1].material = 0;                       // a material
    check(3, 1);
    scene.objects[2].geometry = std::make_shared<const Mesh>(*ball);  // a new mesh, same values
    check(4, 1);
    scene.objects[2].geometry = bare_ball;               // same sizes, fewer attributes
    check(5, 1);
    scene.objects[0].transform.scale = {-1, 1, 1};       // a mirror
    check(6, 1);
    scene.objects.pop_back();                            // another layout
    check(7, 2);
    const auto kept = scene.objects[1].geometry;
    scene.objects[1].geometry = nullptr;                 // an error found before anything is
    EXPECT_THROW(baker.bake(scene), std::invalid_argument);  // written: the last bake stands
    scene.objects[1].geometry = kept;
    check(8, 0);
    scene.objects[0].transform.scale = {0, 1, 1};        // an error while writing
    EXPECT_THROW(baker.bake(scene), std::invalid_argument);
    scene.objects[0].transform.scale = {-1, 1, 1};
    check(9, 2);                                         // nothing of before is trusted
    Mesh broken = *ball;
    broken.indices[4] = uint32_t(broken.positions.size());
    scene.objects[1].geometry = std::make_shared<const Mesh>(broken);  // an index out of range
    EXPECT_THROW(baker.bake(scene), std::invalid_argument);
}

TEST(SceneAnimate, HooksRunWithTheSceneTime) {
    scene::Scene scene = two_objects();
    scene.objects[0].animate = [](scene::Object& o, float t) { o.transform.translation.y = t; };
    scene.animate(2.5f);
    EXPECT_EQ(scene.objects[0].transform.translation.y, 2.5f);
    EXPECT_EQ(scene.objects[1].transform.translation.y, 0.0f);
}
