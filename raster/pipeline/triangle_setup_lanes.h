// Triangle setup (triangle_setup.h) of simd::kLanes triangles at once, for the triangles
// whose vertex box spans less than kSmallExtent sub-pixels per axis (the "small" triangles of
// fixed_point.h, most triangles of a detailed mesh). There every integer setup computes fits
// int32 lanes exactly:
// - the edge deltas |dX|, |dY| < 2^15, so twice the area |dX1 dY2 - dY1 dX2| < 2 * 2^30;
// - the edge function at the pixel box's first pixel centre P is twice the signed area of the
//   triangle (Va, Vb, P), all three within the vertex box grown by half a pixel (P lies in
//   the vertex box itself with one sample, within 128 sub-pixels of it with several), so
//   |E| <= (2^15 + 256)^2 < 2^31, and F = floor(E' / 256) and E' mod 256 (E' = E - 1 on
//   edges that are not top or left) follow with a shift and a mask.
// The depth planes are DepthPlane::from's double arithmetic (depth_plane_coefficients) in a
// loop over the lanes that the compiler vectorises, and the results are those of
// setup_triangle bit for bit (tests/pipeline_triangle_setup_test).
#pragma once
#include <cstdint>

#include "raster/pipeline/triangle_setup.h"
#include "raster/pipeline/vertex_stage.h"
#include "raster/pipeline/viewport.h"
#include "raster/simd/simd.h"

namespace tessera::pipeline {

// The snapped window vertices of kLanes triangles, one lane per triangle, corners in
// submission winding.
struct WindowLanes {
    simd::vint X[3], Y[3];
    simd::vfloat z[3];
};

// Meshes up to this many vertices have their records gathered in lanes (an int32 lane holds
// a record's offset in 32-bit words, 4 per record); larger ones are set up by the scalar path.
inline constexpr size_t kMaxLanesVertices = size_t(1) << 29;

// The corners of kLanes triangles from the vertex stage's records: lane i reads the three
// indices at corners[3 * offset_i ...] (a triangle's indices, relative to a base the caller
// chose so that the offsets are small; consecutive offsets 0, 1, 2, ... are read with vector
// loads when `readable`, the triangles that may be read from the base, is at least kLanes),
// and, where they are below `vertex_count`, the records of those vertices. Returns the lanes
// of `active` whose three indices are valid; `codes` is the union of their corners' outcodes
// (ClipCode). vertex_count must be positive (invalid lanes read vertex 0) and at most
// kMaxLanesVertices.
simd::vmask gather_corners(const uint32_t* corners, simd::vint offset, simd::vmask active, size_t readable,
                           const ProjectedVertex* records, size_t vertex_count, WindowLanes& out, simd::vint& codes);

// The setups of kLanes small triangles, field by field (what setup_small_triangles found).
struct SmallSetups {
    alignas(64) int32_t f[3][simd::kLanes], dx[3][simd::kLanes], dy[3][simd::kLanes], residue[3][simd::kLanes];
    alignas(64) int32_t box[4][simd::kLanes];  // minx, miny, maxx, maxy
    alignas(64) float plane[3][simd::kLanes];    // DepthPlane a, b, c
    alignas(64) int32_t anchor[2][simd::kLanes];  // DepthPlane ax, ay
    // Bit i: edge i is top-left and its constant part a multiple of 256, the two tests of
    // holds_sample() at the pixel centre that almost every edge fails; write() runs the
    // rest (Bezout's gcd) only on these.
    alignas(64) int32_t may_hold_centres[simd::kLanes];
    SetupResult result[simd::kLanes];
    // The same results as lane bits (bit i: lane i), for counting and for visiting the drawn
    // lanes alone: zero_area, culled_face, no_samples, drawn (SetupResult's order).
    uint32_t result_bits[4];

    // Writes the setup of a lane whose result is drawn (triangle and transparent are left to
    // the caller). Written in place: a setup assembled elsewhere and copied would be read
    // back through store forwarding, which fails across its narrow fields.
    void write(int lane, TriangleSetup& out) const;
};

// The part of setup_small_triangles that binning needs: out.result and out.box, not the edge
// functions and depth planes (v.z is not read).
simd::vmask classify_small_triangles(const WindowLanes& v, simd::vmask active, CullMode cull, const Viewport& viewport,
                                     int samples, SmallSetups& out);

// Sets up the triangles of the lanes in `active` that are small. Returns the lanes of `active`
// it did not set up (a vertex box of kSmallExtent or more: setup_triangle's work). For every
// other lane of `active`, out.result[lane] is setup_triangle's result and, when that is
// drawn, out.write(lane, ...) gives its setup.
simd::vmask setup_small_triangles(const WindowLanes& v, simd::vmask active, CullMode cull, const Viewport& viewport,
                                  int samples, SmallSetups& out);

}  // namespace tessera::pipeline
