#include "raster/workloads/sphere_grid.h"

#include <algorithm>
#include <cmath>

#include "raster/workloads/test_meshes.h"

namespace tessera::workloads {
namespace {

constexpr float kRadius = 0.4f;
constexpr size_t kGroundVertices = 4;  // make_sphere_grid's ground is one quad

// Appends `part` scaled by `scale` and moved to `centre`.
void append_placed(Mesh& mesh, const Mesh& part, const glm::vec3& centre, float scale) {
    const auto first = uint32_t(mesh.positions.size());
    for (size_t v = 0; v < part.vertex_count(); ++v) {
        mesh.positions.push_back(centre + scale * part.positions[v]);
        mesh.normals.push_back(part.normals[v]);
        mesh.uvs.push_back(part.uvs[v]);
    }
    for (uint32_t index : part.indices) mesh.indices.push_back(first + index);
}

}  // namespace

void append_ground(Mesh& mesh, float x, float z, float height, float size, int cells) {
    const auto first = uint32_t(mesh.positions.size());
    for (int j = 0; j <= cells; ++j)
        for (int i = 0; i <= cells; ++i) {
            const float u = float(i) / cells, v = float(j) / cells;
            mesh.positions.push_back({x + (u - 0.5f) * size, height, z + (v - 0.5f) * size});
            mesh.normals.push_back({0.0f, 1.0f, 0.0f});
            mesh.uvs.push_back({u, v});
        }
    const auto at = [&](int i, int j) { return first + uint32_t(j * (cells + 1) + i); };
    for (int j = 0; j < cells; ++j)
        for (int i = 0; i < cells; ++i) {
            // Counter-clockwise seen from +y: (x, z) -> (x, z + 1) -> (x + 1, z).
            const uint32_t a = at(i, j), b = at(i + 1, j), c = at(i + 1, j + 1), d = at(i, j + 1);
            mesh.indices.insert(mesh.indices.end(), {a, d, b, b, d, c});
        }
}

SphereGridScene make_sphere_grid(size_t triangles, float aspect) {
    SphereGridScene scene;
    scene.grid = triangles >= 65536 ? 16 : 4;
    // A sphere of 2s slices and s stacks has 4 s (s - 1), about 4 s^2, triangles.
    const double per_sphere = double(triangles) / double(scene.grid * scene.grid);
    scene.sphere_stacks = std::max(3, int(std::lround(std::sqrt(per_sphere / 4.0))));
    scene.sphere_slices = 2 * scene.sphere_stacks;
    const float offset = 0.5f * float(scene.grid - 1);
    Mesh& mesh = scene.mesh;
    const size_t spheres = size_t(scene.grid) * size_t(scene.grid);
    const size_t sphere_vertices = size_t(scene.sphere_slices + 1) * (scene.sphere_stacks + 1);
    mesh.positions.reserve(kGroundVertices + spheres * sphere_vertices + 1);  // +1: Embree padding
    append_ground(mesh, 0.0f, 0.0f, 0.0f, float(scene.grid) + 2.0f, 1);
    const Mesh sphere = workloads::sphere(scene.sphere_slices, scene.sphere_stacks);
    for (int j = 0; j < scene.grid; ++j)
        for (int i = 0; i < scene.grid; ++i)
            append_placed(mesh, sphere, {float(i) - offset, 0.5f, float(j) - offset}, kRadius);
    const float extent = float(scene.grid);
    // Close enough that the ground fills most of the frame, as in the anchors' measurement.
    scene.camera.eye = {0.0f, 0.6f * extent + 0.5f, 0.55f * extent + 1.0f};
    scene.camera.lookat = {0.0f, 0.0f, -0.1f * extent};
    scene.camera.aspect = aspect;
    scene.camera.near = 0.1f;
    scene.camera.far = 4.0f * extent + 10.0f;
    scene.light = {0.6f * extent, 1.5f * extent, 0.3f * extent};
    return scene;
}

void ripple_spheres(SphereGridScene& scene, float time) {
    const int slices = scene.sphere_slices, stacks = scene.sphere_stacks;
    const size_t per_sphere = size_t(slices + 1) * size_t(stacks + 1);
    const float offset = 0.5f * float(scene.grid - 1);
    for (int s = 0; s < scene.grid * scene.grid; ++s) {
        const glm::vec3 centre{float(s % scene.grid) - offset, 0.5f, float(s / scene.grid) - offset};
        glm::vec3* p = scene.mesh.positions.data() + kGroundVertices + size_t(s) * per_sphere;
        const glm::vec3* n = scene.mesh.normals.data() + kGroundVertices + size_t(s) * per_sphere;
        for (size_t v = 0; v < per_sphere; ++v) {
            const float ripple = 0.05f * std::sin(6.0f * n[v].z + 3.0f * time + float(s));
            p[v] = centre + (kRadius + ripple) * n[v];
        }
    }
}

}  // namespace tessera::workloads
