// Procedural meshes for tests, benchmarks and peer comparisons (the llvmpipe benchmark renders
// the same meshes from OBJ files written by `tessera raster --write-mesh`). Everything is
// deterministic in its seed.
//
// Screen-space generators describe triangles in window coordinates (pixels, rows top to
// bottom, window depth in [0, 1]); to_world() maps them back through a view_projection so the
// rasterizer reproduces them (exactly for the identity matrix, up to float rounding otherwise).
#pragma once
#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

#include "raster/core/mesh.h"

namespace tessera::workloads {

struct WindowMesh {
    std::vector<glm::vec3> positions;  // (x, y) pixels, z window depth
    std::vector<uint32_t> indices;
};

// World-space mesh whose image through `view_projection` in a width x height viewport is
// `mesh` (flat normals are not added; uv = window position / size).
Mesh to_world(const WindowMesh& mesh, const glm::mat4& view_projection, int width, int height);

// `count` independent triangles with vertices uniform over [-margin, size + margin] around a
// random centre, edge lengths up to `max_size` pixels, random depths.
WindowMesh random_triangles(uint64_t seed, size_t count, int width, int height, float max_size,
                            float margin = 0.0f);

// Intel MSOC FillrateTest distribution: right triangles with both legs `leg` pixels at random
// positions inside the viewport, alternating orientation, submitted back to front (each one
// nearer than the last, so with depth LESS every fragment passes and writes).
WindowMesh fill_rate(uint64_t seed, size_t count, float leg, int width, int height);

// A closed grid of cells_x x cells_y quads (two triangles each, alternating diagonals)
// covering [x0, x1] x [y0, y1], interior vertices moved by up to `jitter` cells at random
// (vertices on pixel centres when jitter is 0 and the spacing is integral).
WindowMesh grid(uint64_t seed, int cells_x, int cells_y, float x0, float y0, float x1, float y1,
                float jitter);

// A fan of `n` triangles around `centre` covering the disc of `radius` (closed).
WindowMesh fan(glm::vec2 centre, float radius, int n);

// A UV sphere of `segments` x `rings` quads at the origin with radius 1, with normals and uv
// (2 * segments * (rings - 1) triangles, closed).
Mesh sphere(int segments, int rings);

}  // namespace tessera::workloads
