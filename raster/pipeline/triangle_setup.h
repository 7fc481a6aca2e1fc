// Triangle setup (D3D11.3 §3.4): from three snapped window vertices to the
// integer edge functions, the bounding box and the depth plane Z = aX + bY + c that traversal
// steps across pixels. Integer ranges are documented in fixed_point.h.
#pragma once
#include <glm/glm.hpp>

#include <cstdint>

#include "raster/pipeline/fixed_point.h"
#include "raster/pipeline/viewport.h"

namespace tessera::pipeline {

// A vertex after the viewport transform: X, Y in 16.8 fixed point (round to nearest, D3D11.3
// §3.2.4.1), z = window depth.
struct WindowVertex {
    int32_t X = 0, Y = 0;
    float z = 0.0f;
};

// Scalar projection + snap of a clip-space vertex with w > 0; bit-identical to the SIMD
// vertex stage (same float operations, round to nearest even).
WindowVertex project_and_snap(const Viewport& viewport, const glm::vec4& clip);

// Window depth z as the rasterizer's tile buffers hold and compare it: the depth offset
// z - 1, in [-1, 0]. Perspective crowds window depth against 1 (z = 1 - n/d for the far plane
// at infinity, n the near plane, d the distance), where floats are 2^-24 = 6e-8 apart: with
// n = 0.1, two surfaces 10 units away whose depths differ by 1e-8 store the same z, and the
// depth test keeps whichever came first. Floats are dense near 0, so z - 1 = -n/d keeps 24
// bits of n/d at every distance: the reversed-Z argument (Lapidous & Jiao, "Optimal depth
// buffer for low-cost graphics hardware", 1999), in the form that keeps the test LESS and
// the clear value simple (0: the far plane).
inline float window_depth(float offset) { return offset + 1.0f; }

// The depth offset as a plane over pixel centres, anchored at pixel (ax, ay):
//   offset(x, y) = clamp(fma(a, x - ax, fma(b, y - ay, c)), -1, 0)
// with x - ax, y - ay converted to float exactly. The plane is set up on the snapped
// positions (D3D11.3 §3.4.1) in double precision, so that two triangles sharing an edge agree
// on it exactly and order themselves next to it as the coverage rule sees them; every path
// (SIMD tiles, scalar reference) evaluates this same expression, so depths agree to the bit.
struct DepthPlane {
    float a = 0.0f, b = 0.0f, c = 0.0f;
    int16_t ax = 0, ay = 0;  // |window coordinates| < 2^14 (fixed_point.h)

    static DepthPlane from(const WindowVertex& v0, const WindowVertex& v1, const WindowVertex& v2);
    float offset_at(int x, int y) const;
    // At the sample (ox, oy) / 16 pixels from the centre of pixel (x, y) (sample_pattern.h):
    // the same expression with x - ax + ox / 16 and y - ay + oy / 16, still exact in float.
    float offset_at_sample(int x, int y, int ox, int oy) const;
    // Window depth: window_depth() of the above.
    float at(int x, int y) const { return window_depth(offset_at(x, y)); }
    float at_sample(int x, int y, int ox, int oy) const { return window_depth(offset_at_sample(x, y, ox, oy)); }

    // A sample exactly on an edge (the edge function E is 0 there) belongs to the triangle by
    // the top-left rule, which decides as if the sample were moved an infinitesimal step into
    // the triangle. Two triangles that share the edge and lie on the same side of it (a fold
    // at a silhouette, where a back face meets the front face that hides it) then both cover
    // the sample, with exactly the same depth: the edge's. Where coverage looked, just inside
    // the edge, the nearer of the two is the one that hides the other; so a sample on an edge
    // reads its depth there: the plane's value plus edge_step(dX, dY) of each edge it lies on,
    // in edge order, before the clamp. The step is 2^-10 pixel along the edge's inward normal
    // (-dY, dX) / |(dX, dY)|: far above float rounding, well inside the 2^-9 pixel the
    // snapping itself moves vertices by. Both triangles compute the same normal from the same
    // (dX, dY), and the step of each is its own slope along it.
    float edge_step(int32_t dX, int32_t dY) const;
};

// DepthPlane::from's coefficients for a triangle of non-zero area, on plain numbers: corner
// 0 at (X0, Y0), the others relative to it, and the anchor pixel's centre relative to it in
// pixels (cx, cy). Inline so that the lanes setup (triangle_setup_lanes.h) can run it in a loop
// the compiler vectorises, with the same double operations as from().
inline void depth_plane_coefficients(int32_t dX1, int32_t dY1, int32_t dX2, int32_t dY2, float z0, float z1, float z2,
                                     double cx, double cy, float& a, float& b, float& c) {
    // Plane through (X_i / 256, Y_i / 256, z_i) in pixel units; exact in double for the
    // integer parts (|X| <= 2^22), so both windings give the same coefficients.
    const double x1 = double(dX1) / kSubpixels, y1 = double(dY1) / kSubpixels;
    const double x2 = double(dX2) / kSubpixels, y2 = double(dY2) / kSubpixels;
    const double dz1 = double(z1) - double(z0), dz2 = double(z2) - double(z0);
    const double inv_det = 1.0 / (x1 * y2 - x2 * y1);
    const double da = (dz1 * y2 - dz2 * y1) * inv_det;
    const double db = (x1 * dz2 - x2 * dz1) * inv_det;
    a = float(da);
    b = float(db);
    // The depth offset at the anchor pixel's centre, rounded once: z0 - 1 is exact in double.
    c = float((double(z0) - 1.0) + da * cx + db * cy);
}

enum class CullMode { none, back, front };  // front faces are counter-clockwise in NDC (GL)

// Everything traversal needs for one (possibly clipped) triangle.
//
// Edge i runs from vertex i to vertex i+1 of the triangle, oriented so the inside is where all
// three reduced edge functions F_i >= 0 (fixed_point.h). F_i is affine over integer pixel
// coordinates: F_i(x+1, y) = F_i(x, y) - dy[i] and F_i(x, y+1) = F_i(x, y) + dx[i].
struct TriangleSetup {
    int64_t f[3];         // F_i at pixel (minx, miny)
    int32_t dx[3], dy[3]; // edge deltas in sub-pixels
    DepthPlane depth;
    int16_t minx, miny, maxx, maxy;  // inclusive pixel box of the samples, within the viewport
    uint32_t triangle;    // id in the mesh (submission order)
    uint8_t small : 1;        // vertex box < kSmallExtent: int32 traversal anywhere near the box
    uint8_t transparent : 1;  // rasterized after the opaque pass, without depth writes
    uint8_t on_edge : 3;      // bit i: edge i's line runs through pixel centres (holds_centres())
    // Per edge, K mod 256 for the edge's constant K at the pixel centre (triangle_setup.cpp):
    // what the reduced edge function needs to move exactly to another sample of the pixel
    // (sample_offset()).
    uint8_t residue[3];
};
static_assert(sizeof(TriangleSetup) == 80, "bins copy setups: keep them compact");

enum class SetupResult { drawn, zero_area, culled_face, no_samples };

// Sets up triangle v0 v1 v2 (in submission winding) for `viewport`. Returns drawn when `out`
// holds a triangle whose box holds at least one pixel centre of the viewport; a sliver between
// pixel centres may still cover none of them (traversal finds that out).
//
// samples > 1 (multisampling, sample_pattern.h): the box holds the pixels any of whose samples
// may lie within the vertices' box, and "drawn" means it holds at least one pixel.
SetupResult setup_triangle(const WindowVertex& v0, const WindowVertex& v1, const WindowVertex& v2,
                           CullMode cull, const Viewport& viewport, TriangleSetup& out, int samples = 1);

// The change of edge i's function from a pixel centre to the sample (ox, oy) / 16 pixels
// away in E units (256 per unit of F, see holds_sample() below), plus the edge's residue:
// sample_offset() is its floor division by 256.
inline int64_t sample_step(const TriangleSetup& t, int i, int ox, int oy) {
    return int64_t(t.residue[i]) + 16 * (int64_t(t.dx[i]) * oy - int64_t(t.dy[i]) * ox);
}

// How much the reduced edge function F_i of `t` at a pixel changes from the pixel centre to
// the sample (ox, oy) / 16 pixels away: F_i(sample) = F_i(centre) + sample_offset(t, i, ox, oy)
// with the same fill rule, exactly (floor((residue + 16 (dX oy - dY ox)) / 256)).
inline int32_t sample_offset(const TriangleSetup& t, int i, int ox, int oy) {
    return int32_t(sample_step(t, i, ox, oy) >> kSubpixelBits);
}

// Whether that change is a whole number of F units: a sample can lie exactly on edge i
// (holds_sample()) only then.
inline bool sample_step_is_whole(const TriangleSetup& t, int i, int ox, int oy) {
    return (sample_step(t, i, ox, oy) & (kSubpixels - 1)) == 0;
}

// Whether samples can lie exactly on edge i of `t`: the edge function at the centre of pixel
// (x, y) is E = 256 G(x, y) + K with G = dX y - dY x (triangle_setup.cpp), and at the sample
// (ox, oy) / 16 from it E + 16 (dX oy - dY ox). A covered sample with E = 0 lies on a top-left
// edge, and E = 0 has integer solutions exactly when the constant part is a multiple of 256
// whose 256th is a multiple of gcd(dX, dY) (Bezout); then E = 0 is exactly F = 0 (at the
// sample: F + sample_offset() = 0). Only edges between pixel-centred vertices, edges along a
// row or column of centres, and a few in 65536 others qualify; the traversal reads
// DepthPlane::edge_step() only on those. holds_centres() is set up once (TriangleSetup::on_edge).
inline bool holds_centres(const TriangleSetup& t, int i) { return (t.on_edge >> i) & 1; }
bool holds_sample(const TriangleSetup& t, int i, int ox, int oy);

// The depth offset `t` writes at the covered centre of pixel (x, y), or at its sample
// (ox, oy) / 16 pixels away: DepthPlane::offset_at() with DepthPlane::edge_step() of the edges
// the sample lies on (scalar, from the int64 edge functions; what the SIMD traversal
// computes in lanes).
float depth_offset(const TriangleSetup& t, int x, int y);
float depth_offset_at_sample(const TriangleSetup& t, int x, int y, int ox, int oy);

// D3D11.3 §3.4.2.1 top-left rule for an edge with delta (dX, dY) in top-down window
// coordinates whose inside lies where dX*(Py - Ya) - dY*(Px - Xa) > 0: a "left" edge goes up
// the screen (dY < 0), a "top" edge is horizontal with the inside below it (dY == 0, dX > 0).
inline bool is_top_left(int32_t dX, int32_t dY) { return dY < 0 || (dY == 0 && dX > 0); }

}  // namespace tessera::pipeline
