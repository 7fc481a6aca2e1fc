// The vertex stage: world-space mesh positions through view_projection to clip space, the
// clip outcodes, and - for vertices inside the guard band - their snapped window coordinates,
// computed once per vertex rather than once per triangle corner.
//
// Runs in parallel over chunks of vertices (oneTBB); results are independent of the split.
#pragma once
#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

#include <cmath>

#include "raster/core/aligned_vector.h"
#include "raster/core/mesh.h"
#include "raster/simd/simd.h"
#include "raster/pipeline/triangle_setup.h"
#include "raster/pipeline/viewport.h"

namespace tessera::pipeline {

// Outcode bits: which clip planes a vertex lies beyond (clip.h clips against them).
enum ClipCode : uint32_t {
    kClipNear = 1,     // z < -w
    kClipFar = 2,      // z > w
    kClipLeft = 4,     // x < -guard_x * w
    kClipRight = 8,    // x > guard_x * w
    kClipTop = 16,     // y > guard_y * w   (NDC y up = window top)
    kClipBottom = 32,  // y < -guard_y * w
    kClipInvalid = 64  // NaN or infinite coordinate: the triangle is skipped and counted
};

// Clip-space position of p: view_projection * (p, 1), each row evaluated as the fused chain
// m0*x + (m1*y + (m2*z + m3)) so that float and every SIMD width give identical bits.
template <class F>
inline void clip_position(const glm::mat4& m, F px, F py, F pz, F& cx, F& cy, F& cz, F& cw) {
    using std::fma;
    using simd::fma;
    auto row = [&](int r) {
        return fma(F(m[0][r]), px, fma(F(m[1][r]), py, fma(F(m[2][r]), pz, F(m[3][r]))));
    };
    cx = row(0);
    cy = row(1);
    cz = row(2);
    cw = row(3);
}

// Outcode of one clip-space vertex (scalar; the vertex stage computes the same in SIMD).
uint32_t clip_code(const Viewport& viewport, float x, float y, float z, float w);

// What triangle setup reads of a vertex, in one 16-byte record (one cache access per corner
// for meshes whose triangles index vertices far apart).
struct ProjectedVertex {
    WindowVertex window;  // snapped window position and depth (valid when code == 0)
    uint32_t code;        // ClipCode bits
};
static_assert(sizeof(ProjectedVertex) == 16);

// One entry per mesh vertex: clip space as a structure of arrays, plus the projected records.
struct ClipVertices {
    AlignedVector<float> x, y, z, w;  // clip space
    AlignedVector<ProjectedVertex> projected;

    size_t size() const { return x.size(); }
    glm::vec4 clip(size_t i) const { return {x[i], y[i], z[i], w[i]}; }
};

// Fills `out` (resized to mesh.vertex_count()).
void run_vertex_stage(const Mesh& mesh, const glm::mat4& view_projection, const Viewport& viewport,
                      ClipVertices& out);

}  // namespace tessera::pipeline
