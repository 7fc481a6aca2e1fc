// Perspective-correct barycentrics at pixel centres from a triangle's CLIP-SPACE vertices: the
// visibility-buffer (homogeneous rasterization) formulation, so it needs neither the clipped
// polygon nor the snapped vertices and is valid for near-clipped triangles and for the Embree
// path alike (both shade with this code).
//
// With h_i = (x_i, y_i, w_i) the clip-space vertices and p = (x_ndc, y_ndc, 1) the pixel's
// view ray, the point of the triangle's plane seen through p is sum(l_i * c_i) with
// sum(l_i * h_i) proportional to p, i.e. l proportional to M^-1 p (M = [h0 h1 h2]). Row i of
// the adjugate of M is h_j x h_k, so r_i = (h_j x h_k) . p and l_i = r_i / (r_0 + r_1 + r_2):
// the l_i are the barycentrics of the surface point (interpolate any attribute with them; the
// textbook "interpolate u/h, v/h, 1/h linearly, divide" in closed form).
#pragma once
#include <glm/glm.hpp>

#include <cmath>

#include "raster/core/mesh.h"
#include "raster/simd/simd.h"
#include "raster/pipeline/vertex_stage.h"
#include "raster/pipeline/viewport.h"

namespace tessera::pipeline {

struct PerspectiveBarycentrics {
    // r_i(x, y) = e[i].x * x + e[i].y * y + e[i].z in window pixel coordinates (pixel centre of
    // column c is x = c + 0.5, rows top to bottom).
    glm::vec3 e[3]{};

    // `width` x `height`: the viewport (window = ((x_ndc + 1) W/2, (1 - y_ndc) H/2)).
    static PerspectiveBarycentrics from_clip(const glm::vec4& c0, const glm::vec4& c1, const glm::vec4& c2,
                                             int width, int height) {
        const glm::dvec3 h[3] = {{c0.x, c0.y, c0.w}, {c1.x, c1.y, c1.w}, {c2.x, c2.y, c2.w}};
        // x_ndc = 2x/W - 1, y_ndc = 1 - 2y/H folded into the coefficients.
        const double sx = 2.0 / width, sy = -2.0 / height;
        PerspectiveBarycentrics b;
        for (int i = 0; i < 3; ++i) {
            const glm::dvec3 n = glm::cross(h[(i + 1) % 3], h[(i + 2) % 3]);
            b.e[i] = glm::vec3(float(n.x * sx), float(n.y * sy), float(n.z - n.x + n.y));
        }
        return b;
    }

    // Barycentrics at window positions (x, y) (float or simd::vfloat). Where the view ray is
    // parallel to the triangle's plane the result is not finite (such pixels are not covered).
    template <class F>
    void at(F x, F y, F& l0, F& l1, F& l2) const {
        using simd::fma;
        using std::fma;
        const F r0 = fma(F(e[0].x), x, fma(F(e[0].y), y, F(e[0].z)));
        const F r1 = fma(F(e[1].x), x, fma(F(e[1].y), y, F(e[1].z)));
        const F r2 = fma(F(e[2].x), x, fma(F(e[2].y), y, F(e[2].z)));
        const F inv = F(1.0f) / (r0 + r1 + r2);
        l0 = r0 * inv;
        l1 = r1 * inv;
        l2 = r2 * inv;
    }
};

// Barycentrics of triangle `id` of `mesh` from the clip-space vertices the rasterizer computed
// (TileContext::clip, Rasterizer::clip_vertices()). The Embree path computes the clip-space
// positions with clip_position() (vertex_stage.h) from the same world positions and passes
// them to from_clip(): same bits, same coefficients.
inline PerspectiveBarycentrics triangle_barycentrics(const Mesh& mesh, const ClipVertices& clip, uint32_t id,
                                                     const Viewport& viewport) {
    const uint32_t* index = &mesh.indices[3 * size_t(id)];
    return PerspectiveBarycentrics::from_clip(clip.clip(index[0]), clip.clip(index[1]), clip.clip(index[2]),
                                              viewport.width, viewport.height);
}

}  // namespace tessera::pipeline
