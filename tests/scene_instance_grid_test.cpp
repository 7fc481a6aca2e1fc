// A grid of copies of a scene (scene/instance_grid.h), as `tessera compare --sweep` grows the
// user's content: exact triangle counts, copies that never overlap, bounds that hold them all.
#include <gtest/gtest.h>

#include <memory>

#include "raster/geometry/box.h"
#include "raster/scene/instance_grid.h"

using namespace tessera;

namespace {

scene::Scene two_objects() {
    scene::Scene s;
    s.materials.resize(2);
    auto box = std::make_shared<const Mesh>(geometry::box_mesh(glm::vec3(1.0f, 0.5f, 0.25f)));
    scene::Object a;
    a.geometry = box;
    scene::Object b = a;
    b.material = 1;
    b.transform.translation = glm::vec3(0.0f, 2.0f, 0.0f);
    b.animate = [](scene::Object& o, float) { o.transform.translation = glm::vec3(0.0f); };
    s.objects = {a, b};
    return s;
}

TEST(InstanceGrid, TriangleCountsAreExactMultiples) {
    const scene::Scene s = two_objects();
    const size_t one = scene::bake(s).mesh.triangle_count();
    ASSERT_GT(one, 0u);
    for (int copies : {1, 2, 3, 7, 16}) {
        const scene::InstanceGrid grid(copies, glm::vec3(-1.0f, -0.5f, -0.25f), glm::vec3(1.0f, 2.5f, 0.25f));
        const scene::Scene copied = scene::instance_grid(s, grid);
        EXPECT_EQ(copied.objects.size(), 2u * size_t(copies));
        EXPECT_EQ(scene::bake(copied).mesh.triangle_count(), one * size_t(copies)) << copies;
        for (const scene::Object& o : copied.objects) EXPECT_FALSE(o.animate);  // a still frame
    }
}

TEST(InstanceGrid, CopiesDoNotOverlapAndFitTheBounds) {
    const glm::vec3 lower(-1.0f, -0.5f, -0.25f), upper(1.0f, 2.5f, 0.25f);
    const scene::InstanceGrid grid(7, lower, upper);
    EXPECT_EQ(grid.columns, 3);
    EXPECT_EQ(grid.rows, 3);
    EXPECT_GT(grid.cell.x, upper.x - lower.x);  // a gap between neighbours
    EXPECT_GT(grid.cell.y, upper.z - lower.z);
    const auto [all_lower, all_upper] = grid.bounds(lower, upper);
    const Mesh baked = scene::bake(scene::instance_grid(two_objects(), grid)).mesh;
    glm::vec3 lo(1e30f), hi(-1e30f);
    for (const glm::vec3& p : baked.positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
    for (int k = 0; k < 3; ++k) {
        EXPECT_NEAR(lo[k], all_lower[k], 1e-5f) << k;
        EXPECT_NEAR(hi[k], all_upper[k], 1e-5f) << k;
    }
    // Copy 0 is the original, in place.
    EXPECT_EQ(grid.offset(0), glm::vec3(0.0f));
}

TEST(InstanceGrid, FlatContentStillGetsAGapAndBadInputIsRefused) {
    const scene::InstanceGrid flat(4, glm::vec3(0.0f), glm::vec3(1.0f, 1.0f, 0.0f));  // no depth along z
    EXPECT_GT(flat.cell.y, 0.0f);
    EXPECT_THROW(scene::InstanceGrid(0, glm::vec3(0.0f), glm::vec3(1.0f)), std::invalid_argument);
    EXPECT_THROW(scene::InstanceGrid(2, glm::vec3(0.0f), glm::vec3(NAN)), std::invalid_argument);
}

}  // namespace
