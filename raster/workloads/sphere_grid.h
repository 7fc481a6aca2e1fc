// The benchmark scene of research/rasterizer-anchors.md 3.2: a ground plane under a g x g grid
// of UV spheres (workloads::sphere, the usual (cos 2pi u sin pi v, ...) parametrisation), sized
// to a requested triangle count. Tests and bench_raytrace use it so the rasterizer and Embree
// are compared on the anchors' workload.
#pragma once
#include <cstddef>

#include "raster/core/camera.h"
#include "raster/core/mesh.h"

namespace tessera::workloads {

// Appends a square in the plane y = height, centred on (x, z), `cells` x `cells` quads,
// facing +y.
void append_ground(Mesh& mesh, float x, float z, float height, float size, int cells);

struct SphereGridScene {
    Mesh mesh;
    Camera camera;      // looks down at the grid from the front, above
    glm::vec3 light;    // a point light above and to the side (casts visible shadows)
    int grid = 0;       // spheres per side; sphere (i, j) sits at (i, 0.5, j) - offset
    int sphere_slices = 0;
    int sphere_stacks = 0;
};

// About `triangles` triangles (at least the ground's 2 and 24 per sphere); positions have
// the spare capacity Embree needs to share them (scene.h).
SphereGridScene make_sphere_grid(size_t triangles, float aspect = 16.0f / 9.0f);

// Moves every sphere vertex along its radius by a time-dependent ripple (same topology):
// the stand-in for an animated, deforming mesh in the refit-versus-rebuild measurement.
void ripple_spheres(SphereGridScene& scene, float time);

}  // namespace tessera::workloads
