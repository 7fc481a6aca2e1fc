// A ray scene built by parts (one Embree geometry per object of a baked scene): hits name the
// mesh's triangle ids, an update rebuilds exactly the parts that changed, and whatever was
// kept or rebuilt, the visibility is that of a scene built afresh over the same mesh.
#include <gtest/gtest.h>

#include <vector>

#include "raster/core/pixel_rays.h"
#include "raster/embree/device.h"
#include "raster/embree/ray_cast.h"
#include "raster/embree/scene.h"
#include "raster/workloads/sphere_grid.h"

namespace tessera::embree {
namespace {

// Three objects: a grid of spheres on its ground quad, the same grid moved right and up (no
// coplanar grounds: which of two coincident triangles a ray reports depends on the BVH), a
// floor quad under both.
struct PartedMesh {
    Mesh mesh;
    std::vector<MeshPart> parts;
    Camera camera;
};

void append(PartedMesh& into, const Mesh& object, glm::vec3 offset) {
    MeshPart part{into.mesh.vertex_count(), object.vertex_count(), into.mesh.triangle_count(),
                  object.triangle_count()};
    for (const glm::vec3& p : object.positions) into.mesh.positions.push_back(p + offset);
    for (uint32_t i : object.indices) into.mesh.indices.push_back(uint32_t(part.first_vertex) + i);
    into.parts.push_back(part);
}

PartedMesh three_objects() {
    const workloads::SphereGridScene grid = workloads::make_sphere_grid(3000);
    PartedMesh m;
    m.camera = grid.camera;
    append(m, grid.mesh, glm::vec3(0.0f));
    append(m, grid.mesh, glm::vec3(1.5f, 0.25f, -0.5f));
    Mesh floor;
    floor.positions = {{-20, -0.2f, -20}, {20, -0.2f, -20}, {20, -0.2f, 20}, {-20, -0.2f, 20}};
    floor.indices = {0, 2, 1, 0, 3, 2};
    append(m, floor, glm::vec3(0.0f));
    return m;
}

VisibilityBuffer visibility(const RayScene& scene, const Camera& camera, std::span<const uint8_t> skip = {}) {
    VisibilityBuffer out;
    cast_primary_rays(scene, camera.view_projection(), 128, 72, out, RayPacket::x16, skip);
    return out;
}

void expect_same(const VisibilityBuffer& a, const VisibilityBuffer& b) {
    EXPECT_EQ(a.triangle, b.triangle);
    EXPECT_EQ(a.depth, b.depth);
}

TEST(EmbreeParts, HitsNameTheMeshsTrianglesAsOneGeometryDoes) {
    PartedMesh m = three_objects();
    const RayScene parted(default_ray_device(), m.mesh, m.parts);
    EXPECT_EQ(parted.parts_built(), 3u);
    reserve_ray_padding(m.mesh);
    const RayScene whole(default_ray_device(), m.mesh);
    const VisibilityBuffer a = visibility(parted, m.camera), b = visibility(whole, m.camera);
    expect_same(a, b);
    // Every part shows, so each one's ids were mapped (not just the first part's).
    std::vector<size_t> seen(m.parts.size(), 0);
    for (uint32_t t : a.triangle)
        for (size_t p = 0; p < m.parts.size(); ++p)
            seen[p] += t != kNoTriangle && t >= m.parts[p].first_triangle &&
                       t < m.parts[p].first_triangle + m.parts[p].triangle_count;
    for (size_t p = 0; p < m.parts.size(); ++p) EXPECT_GT(seen[p], 50u) << "part " << p;
    // Skip flags are per mesh triangle too: skipping the second grid shows the floor there.
    std::vector<uint8_t> skip(m.mesh.triangle_count(), 0);
    for (size_t t = 0; t < m.parts[1].triangle_count; ++t) skip[m.parts[1].first_triangle + t] = 1;
    expect_same(visibility(parted, m.camera, skip), visibility(whole, m.camera, skip));
}

TEST(EmbreeParts, UpdateRebuildsOnlyWhatChangedAndMatchesAFreshScene) {
    PartedMesh m = three_objects();
    RayScene scene(default_ray_device(), m.mesh, m.parts);
    const VisibilityBuffer before = visibility(scene, m.camera);

    // The next frame: an equal mesh in a new buffer, nothing to build.
    PartedMesh same = m;
    scene.update(same.mesh, same.parts);
    EXPECT_EQ(scene.parts_built(), 0u);
    expect_same(visibility(scene, m.camera), before);

    // The second grid moves: only it is rebuilt, and the picture follows.
    PartedMesh moved = m;
    for (size_t v = 0; v < moved.parts[1].vertex_count; ++v)
        moved.mesh.positions[moved.parts[1].first_vertex + v] += glm::vec3(-0.7f, 0.3f, 0.0f);
    scene.update(moved.mesh, moved.parts);
    EXPECT_EQ(scene.parts_built(), 1u);
    const VisibilityBuffer after = visibility(scene, m.camera);
    EXPECT_NE(after.triangle, before.triangle);
    expect_same(after, visibility(RayScene(default_ray_device(), moved.mesh, moved.parts), m.camera));

    // Same positions, one triangle's corners turned: its indices changed, so it is rebuilt.
    PartedMesh turned = moved;
    uint32_t* first = &turned.mesh.indices[3 * turned.parts[0].first_triangle];
    std::swap(first[1], first[2]);
    scene.update(turned.mesh, turned.parts);
    EXPECT_EQ(scene.parts_built(), 1u);

    // Objects added, removed and resized: the first grid loses its last sphere's worth of
    // triangles and the floor goes.
    PartedMesh fewer = moved;
    fewer.parts.pop_back();
    fewer.parts[0].triangle_count -= 200;
    scene.update(fewer.mesh, fewer.parts);
    EXPECT_EQ(scene.parts_built(), 1u);
    expect_same(visibility(scene, m.camera), visibility(RayScene(default_ray_device(), fewer.mesh, fewer.parts), m.camera));
    scene.update(m.mesh, m.parts);
    EXPECT_EQ(scene.parts_built(), 3u);
    expect_same(visibility(scene, m.camera), before);
}

TEST(EmbreeParts, EmptyAndBrokenPartsAndBadRanges) {
    PartedMesh m = three_objects();
    std::vector<MeshPart> parts = m.parts;
    parts.insert(parts.begin() + 1, MeshPart{m.parts[1].first_vertex, 0, m.parts[1].first_triangle, 0});
    // An index below the part's first vertex is out of the part: skipped and counted.
    m.mesh.indices[3 * m.parts[1].first_triangle] = 0;
    const RayScene scene(default_ray_device(), m.mesh, parts);
    EXPECT_EQ(scene.parts_built(), 3u);
    EXPECT_EQ(scene.defects().bad_index, 1u);
    VisibilityBuffer out = visibility(scene, m.camera);
    for (uint32_t t : out.triangle) EXPECT_TRUE(t == kNoTriangle || t < m.mesh.triangle_count());
    parts.back().triangle_count += 1;
    EXPECT_THROW(RayScene(default_ray_device(), m.mesh, parts), std::invalid_argument);
}

}  // namespace
}  // namespace tessera::embree
