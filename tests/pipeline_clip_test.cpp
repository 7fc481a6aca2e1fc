// Homogeneous clipping (raster/pipeline/clip.h) against its definition: the output polygon lies
// on the input triangle, inside every clip plane, with each new vertex on a plane it was cut
// at; it is convex and keeps the triangle's winding; it is exactly the part of the triangle
// inside the volume (sampled); a shared edge is cut at the same bits from both sides; and cut
// points at an exactly representable parameter are exact.
#include <gtest/gtest.h>

#include <glm/glm.hpp>

#include <algorithm>
#include <array>
#include <bit>
#include <cfloat>
#include <cmath>
#include <vector>

#include "pipeline_fixtures.h"
#include "raster/pipeline/clip.h"
#include "raster/pipeline/vertex_stage.h"

namespace tessera::pipeline {
namespace {

using test::Rng;

// The clip volume of clip.h and vertex_stage.h's outcodes, as planes dot(n, v) >= 0 inside.
struct Plane {
    uint32_t bit;
    glm::dvec4 n;
};
std::array<Plane, 6> clip_planes(const Viewport& vp) {
    const double gx = vp.guard_x, gy = vp.guard_y;
    return {{{kClipNear, {0, 0, 1, 1}},     // z >= -w
             {kClipFar, {0, 0, -1, 1}},     // z <= w
             {kClipLeft, {1, 0, 0, gx}},    // x >= -guard_x * w
             {kClipRight, {-1, 0, 0, gx}},  // x <= guard_x * w
             {kClipTop, {0, -1, 0, gy}},    // y <= guard_y * w
             {kClipBottom, {0, 1, 0, gy}}}};  // y >= -guard_y * w
}
double distance(const Plane& p, const glm::dvec4& v) { return glm::dot(p.n, v); }
// The size of the terms of distance(): float rounding of v is relative to it.
double scale(const Plane& p, const glm::dvec4& v) { return glm::dot(glm::abs(p.n), glm::abs(v)); }

bool same_bits(const glm::vec4& a, const glm::vec4& b) {
    for (int i = 0; i < 4; ++i)
        if (std::bit_cast<uint32_t>(a[i]) != std::bit_cast<uint32_t>(b[i])) return false;
    return true;
}

// Barycentric coordinates (l1, l2) of v with respect to the triangle: v = a + l1 (b - a) +
// l2 (c - a) in the least-squares sense (4 equations), and the residual's size.
struct Barycentric {
    double l1, l2, residual;
};
Barycentric barycentric(const glm::dvec4 t[3], const glm::dvec4& v) {
    const glm::dvec4 e1 = t[1] - t[0], e2 = t[2] - t[0], r = v - t[0];
    const double g11 = glm::dot(e1, e1), g12 = glm::dot(e1, e2), g22 = glm::dot(e2, e2);
    const double det = g11 * g22 - g12 * g12;
    const double l1 = (glm::dot(e1, r) * g22 - glm::dot(e2, r) * g12) / det;
    const double l2 = (glm::dot(e2, r) * g11 - glm::dot(e1, r) * g12) / det;
    return {l1, l2, glm::length(r - l1 * e1 - l2 * e2)};
}

// A clip-space vertex of one of several kinds: inside the frustum or crossing near/far, far
// beyond the guard band, or anywhere around the eye (w <= 0 included).
glm::vec4 random_vertex(Rng& rng, int kind) {
    auto in = [&](double lo, double hi) { return float(lo + (hi - lo) * rng.unit()); };
    switch (kind) {
        case 0: {
            const float w = in(0.1, 10.0);
            return {w * in(-1.5, 1.5), w * in(-1.5, 1.5), w * in(-2.0, 2.0), w};
        }
        case 1: {
            const float w = in(0.1, 10.0);
            return {w * in(-200.0, 200.0), w * in(-200.0, 200.0), w * in(-1.2, 1.2), w};
        }
        default:
            return {in(-5.0, 5.0), in(-5.0, 5.0), in(-5.0, 5.0), in(-5.0, 5.0)};
    }
}

uint32_t codes_of(const Viewport& vp, const glm::vec4 v[3]) {
    uint32_t codes = 0;
    for (int i = 0; i < 3; ++i) codes |= clip_code(vp, v[i].x, v[i].y, v[i].z, v[i].w);
    return codes;
}

// Everything clip.h promises about the polygon `out[0 .. n)` clipped from `in` against
// `codes`, plus the exact region it covers, checked at `samples` random points of the triangle.
// Without `geometry` (inputs near FLT_MAX, where the cut points lose their accuracy), only
// what the integer ranges rely on: a polygon of at most kMaxClippedVertices vertices, each
// projecting inside the guard band.
void expect_valid_clip(const Viewport& vp, const glm::vec4 in[3], uint32_t codes, const glm::vec4* out, int n,
                       Rng& rng, int samples, bool geometry = true) {
    const auto planes = clip_planes(vp);
    const glm::dvec4 t[3] = {in[0], in[1], in[2]};
    double size = 0.0;
    for (const glm::dvec4& v : t) size = std::max(size, glm::length(v));
    // Float rounding of a few cuts, relative to the input's size (a cut point can be much
    // shorter than the vertices it is interpolated from: near the eye, where w -> 0).
    constexpr double kTol = 1e-5;
    ASSERT_TRUE(n == 0 || (n >= 3 && n <= kMaxClippedVertices)) << n;
    std::vector<Barycentric> bary;
    for (int k = 0; k < n; ++k) {
        const glm::dvec4 v = out[k];
        // Projectable, inside the guard band's window coordinates (fixed_point.h's ranges).
        ASSERT_GE(out[k].w, FLT_MIN);
        float wx, wy, wz;
        vp.to_window(out[k].x, out[k].y, out[k].z, out[k].w, wx, wy, wz);
        ASSERT_LE(std::fabs(wx), kCoordLimit * 1.01f);
        ASSERT_LE(std::fabs(wy), kCoordLimit * 1.01f);
        ASSERT_TRUE(std::isfinite(wz));
        if (!geometry) continue;
        // Inside every plane; a vertex that is not an input vertex lies on a plane it was cut at.
        bool on_a_cut_plane = false;
        for (const Plane& p : planes) {
            const double d = distance(p, v), s = scale(p, v) + scale(p, glm::dvec4(size));
            ASSERT_GE(d, -kTol * s) << "vertex " << k << " outside plane " << p.bit;
            on_a_cut_plane |= (codes & p.bit) && std::fabs(d) <= kTol * s;
        }
        const bool original = same_bits(out[k], in[0]) || same_bits(out[k], in[1]) || same_bits(out[k], in[2]);
        ASSERT_TRUE(original || on_a_cut_plane) << "vertex " << k << " is neither an input vertex nor on a plane";
        // On the triangle.
        const Barycentric b = barycentric(t, v);
        ASSERT_LE(b.residual, kTol * size) << "vertex " << k << " off the triangle's plane";
        ASSERT_GE(b.l1, -kTol);
        ASSERT_GE(b.l2, -kTol);
        ASSERT_LE(b.l1 + b.l2, 1.0 + kTol);
        bary.push_back(b);
    }
    // Convex and in the triangle's winding: in barycentric coordinates the triangle is
    // (0,0), (1,0), (0,1), counter-clockwise, so every corner of the polygon turns left.
    auto turn = [&](int i, int j, int k) {
        return (bary[j].l1 - bary[i].l1) * (bary[k].l2 - bary[i].l2) -
               (bary[j].l2 - bary[i].l2) * (bary[k].l1 - bary[i].l1);
    };
    if (!geometry) return;
    for (int k = 0; k < n; ++k) ASSERT_GE(turn(k, (k + 1) % n, (k + 2) % n), -kTol) << "corner " << k;
    // The polygon is the part of the triangle inside the volume: random points of the triangle
    // away from every plane and polygon edge are inside both or outside both.
    for (int s = 0; s < samples; ++s) {
        double l1 = rng.unit(), l2 = rng.unit();
        if (l1 + l2 > 1.0) l1 = 1.0 - l1, l2 = 1.0 - l2;
        const glm::dvec4 p = t[0] + l1 * (t[1] - t[0]) + l2 * (t[2] - t[0]);
        bool inside_volume = true, near_a_plane = false;
        for (const Plane& q : planes) {
            const double d = distance(q, p), margin = 1e-4 * (scale(q, p) + scale(q, glm::dvec4(size)));
            inside_volume &= d >= 0.0;
            near_a_plane |= std::fabs(d) <= margin;
        }
        if (near_a_plane) continue;
        bool inside_polygon = n >= 3, near_an_edge = false;
        for (int k = 0; k < n; ++k) {
            const Barycentric &a = bary[k], &b = bary[(k + 1) % n];
            const double len = std::hypot(b.l1 - a.l1, b.l2 - a.l2);
            if (len < 1e-9) continue;
            const double side = ((b.l1 - a.l1) * (l2 - a.l2) - (b.l2 - a.l2) * (l1 - a.l1)) / len;
            inside_polygon &= side >= 0.0;
            near_an_edge |= std::fabs(side) <= 1e-4;
        }
        if (near_an_edge) continue;
        ASSERT_EQ(inside_polygon, inside_volume) << "sample (" << l1 << ", " << l2 << ") of " << n << " vertices";
    }
}

TEST(PipelineClip, RandomTrianglesClipToThePartInsideTheVolume) {
    const Viewport vp(640, 480);
    Rng rng(16101);
    int clipped = 0, empty = 0, most = 0;
    for (int i = 0; i < 4000; ++i) {
        glm::vec4 in[3];
        const int kind = i % 4;
        for (glm::vec4& v : in) v = random_vertex(rng, kind == 3 ? int(rng.uniform(0, 2)) : kind);
        const uint32_t codes = codes_of(vp, in);
        if (codes == 0) continue;
        glm::vec4 out[kMaxClippedVertices];
        const int n = clip_triangle(in, codes, vp, out);
        expect_valid_clip(vp, in, codes, out, n, rng, 64);
        if (HasFatalFailure()) {
            ADD_FAILURE() << "triangle " << i << " codes " << codes;
            return;
        }
        ++clipped;
        empty += n == 0;
        most = std::max(most, n);
    }
    EXPECT_GT(clipped, 2000);
    EXPECT_GT(empty, 100);
    EXPECT_GE(most, 6);
}

// Two triangles sharing edge (a, b) in opposite directions: every vertex one of them makes on
// that edge, the other makes with the same bits (no cracks between clipped neighbours).
TEST(PipelineClip, SharedEdgeIsCutAtTheSameBitsFromBothSides) {
    const Viewport vp(640, 480);
    Rng rng(16102);
    int shared_cuts = 0;
    for (int i = 0; i < 3000; ++i) {
        const int kind = i % 3;
        const glm::vec4 a = random_vertex(rng, kind), b = random_vertex(rng, kind);
        const glm::vec4 c = random_vertex(rng, kind), d = random_vertex(rng, kind);
        const glm::vec4 first[3] = {a, b, c}, second[3] = {b, a, d};
        glm::vec4 out1[kMaxClippedVertices], out2[kMaxClippedVertices];
        // Each against its own planes, as the primitive stage clips them.
        const int n1 = clip_triangle(first, codes_of(vp, first), vp, out1);
        const int n2 = clip_triangle(second, codes_of(vp, second), vp, out2);
        const glm::dvec4 t1[3] = {a, b, c}, t2[3] = {b, a, d};
        // Vertices on segment ab: barycentric weight of the third vertex zero.
        auto on_ab = [](const glm::dvec4 t[3], const glm::vec4& v) {
            const Barycentric w = barycentric(t, v);
            return std::fabs(w.l2) < 1e-7 && w.residual < 1e-6 * glm::length(t[0] - t[1]);
        };
        auto found = [](const glm::vec4& v, const glm::vec4* out, int n) {
            for (int k = 0; k < n; ++k)
                if (same_bits(v, out[k])) return true;
            return false;
        };
        for (int k = 0; k < n1; ++k) {
            if (!on_ab(t1, out1[k]) || same_bits(out1[k], a) || same_bits(out1[k], b)) continue;
            ++shared_cuts;
            EXPECT_TRUE(found(out1[k], out2, n2)) << "triangle " << i;
        }
        for (int k = 0; k < n2; ++k) {
            if (!on_ab(t2, out2[k]) || same_bits(out2[k], a) || same_bits(out2[k], b)) continue;
            EXPECT_TRUE(found(out2[k], out1, n1)) << "triangle " << i;
        }
    }
    EXPECT_GT(shared_cuts, 500);
}

// A cut at a parameter that is a power of two gives the interpolated vertex exactly, and the
// polygon keeps the triangle's order: a, the cut of ab, the cut of bc, c.
TEST(PipelineClip, CutAtAnExactParameterIsExact) {
    const Viewport vp(640, 480);
    const glm::vec4 a(0.0f, 0.0f, 0.0f, 1.0f);    // z + w = 1
    const glm::vec4 b(8.0f, -4.0f, -5.0f, 2.0f);  // z + w = -3: t = 1 / 4 from a and from c
    const glm::vec4 c(0.0f, 1.0f, 0.0f, 1.0f);    // z + w = 1
    const glm::vec4 in[3] = {a, b, c};
    ASSERT_EQ(codes_of(vp, in), uint32_t(kClipNear));
    glm::vec4 out[kMaxClippedVertices];
    ASSERT_EQ(clip_triangle(in, kClipNear, vp, out), 4);
    EXPECT_TRUE(same_bits(out[0], a));
    EXPECT_TRUE(same_bits(out[1], a + 0.25f * (b - a)));
    EXPECT_TRUE(same_bits(out[2], glm::vec4(2.0f, -0.25f, -1.25f, 1.25f)));  // c + (b - c) / 4
    EXPECT_TRUE(same_bits(out[3], c));
    EXPECT_EQ(out[1], glm::vec4(2.0f, -1.0f, -1.25f, 1.25f));
}

TEST(PipelineClip, HandPickedCases) {
    const Viewport vp(640, 480);
    glm::vec4 out[kMaxClippedVertices];
    // No plane named: the triangle comes back as it is, even partly off the viewport (inside
    // the guard band: only triangles leaving the band are clipped at x and y).
    const glm::vec4 inside[3] = {{-3.0f, 0.0f, 0.5f, 1.0f}, {0.5f, 2.0f, 0.0f, 1.0f}, {0.25f, -0.5f, -0.5f, 2.0f}};
    ASSERT_EQ(codes_of(vp, inside), 0u);
    ASSERT_EQ(clip_triangle(inside, 0, vp, out), 3);
    for (int i = 0; i < 3; ++i) EXPECT_TRUE(same_bits(out[i], inside[i]));

    // All three vertices behind the same plane: nothing left.
    const glm::vec4 behind[3] = {{0, 0, 0, -1}, {1, 0, 0, -2}, {0, 1, 0, -1}};
    EXPECT_EQ(clip_triangle(behind, codes_of(vp, behind), vp, out), 0);

    // Crossing w = 0 (z = 1.05 w - 1.025, a perspective projection with near 0.5 and far 20):
    // the visible part is kept, every vertex in front of the eye.
    const glm::vec4 crossing[3] = {{0, 0, 0.025f, 1}, {0.5f, 0, -2.075f, -1}, {0, 0.5f, 0.025f, 1}};
    const int n = clip_triangle(crossing, codes_of(vp, crossing), vp, out);
    ASSERT_EQ(n, 4);
    for (int i = 0; i < n; ++i) EXPECT_GT(out[i].w, 0.4f);
    Rng rng(16103);
    expect_valid_clip(vp, crossing, codes_of(vp, crossing), out, n, rng, 1000);

    // A triangle lying in a plane counts as inside it.
    const glm::vec4 on_near[3] = {{0, 0, -1, 1}, {0.5f, 0, -1, 1}, {0, 0.5f, -1, 1}};
    EXPECT_EQ(clip_triangle(on_near, kClipNear, vp, out), 3);

    // Beyond the guard band on the right: cut at x = guard_x * w, which projects to the
    // band's edge at kCoordLimit pixels.
    const glm::vec4 wide[3] = {{0, 0, 0, 1}, {200.0f, 0.0f, 0, 1}, {0, 1, 0, 1}};
    ASSERT_EQ(codes_of(vp, wide), uint32_t(kClipRight));
    const int m = clip_triangle(wide, kClipRight, vp, out);
    ASSERT_EQ(m, 4);
    float wx, wy, wz;
    vp.to_window(out[1].x, out[1].y, out[1].z, out[1].w, wx, wy, wz);
    EXPECT_NEAR(wx, kCoordLimit, kCoordLimit * 1e-6f);

    // Extreme but finite coordinates: a valid polygon or nothing, never NaN or infinity.
    for (int i = 0; i < 500; ++i) {
        glm::vec4 in[3];
        for (glm::vec4& v : in)
            for (int k = 0; k < 4; ++k) {
                const float big = rng.chance(50) ? FLT_MAX : 1e30f;
                v[k] = rng.chance(30) ? (rng.chance(50) ? big : -big) : 4.0f * rng.unit() - 2.0f;
            }
        const uint32_t codes = codes_of(vp, in);
        if (codes & kClipInvalid) continue;
        const int k = clip_triangle(in, codes, vp, out);
        expect_valid_clip(vp, in, codes, out, k, rng, 0, false);
        if (HasFatalFailure()) return;
    }
}

}  // namespace
}  // namespace tessera::pipeline
