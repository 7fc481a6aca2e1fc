// What the pipeline unit tests share: random snapped triangles of every size class, and the
// D3D11.3 coverage of a pixel written out from the definition in exact integer arithmetic (no
// part of triangle_setup), which setup, binning and tile raster are checked against.
#pragma once
#include <algorithm>
#include <cstdint>
#include <initializer_list>
#include <vector>

#include "seeded_random.h"
#include "raster/pipeline/triangle_setup.h"

namespace tessera::test {

// Sub-pixel coordinate of the centre of pixel x (16.8 fixed point).
inline int64_t pixel_centre(int x) { return int64_t(x) * pipeline::kSubpixels + pipeline::kSubpixels / 2; }

// Twice the signed area of (a, b, p) in sub-pixels^2, exact (|.| <= 2^47 within the guard band).
inline int64_t orient(const pipeline::WindowVertex& a, const pipeline::WindowVertex& b, int64_t px, int64_t py) {
    return (int64_t(b.X) - a.X) * (py - a.Y) - (int64_t(b.Y) - a.Y) * (px - a.X);
}

// D3D11.3 §3.4.2.1 for edge p -> q of a triangle whose third vertex is r, from the geometry
// (either winding): a top edge is horizontal with the third vertex below it (window y runs
// down); a left edge is not horizontal and has the third vertex to the right of its line.
inline bool is_top_or_left(const pipeline::WindowVertex& p, const pipeline::WindowVertex& q,
                           const pipeline::WindowVertex& r) {
    if (p.Y == q.Y) return r.Y > p.Y;
    // The edge's line at the height of r is at x = p.X + (r.Y - p.Y) * (q.X - p.X) / (q.Y - p.Y)
    // and r.X exceeds it; multiplied out by (q.Y - p.Y), whose sign turns the comparison.
    const int64_t lhs = (int64_t(r.X) - p.X) * (int64_t(q.Y) - p.Y);
    const int64_t rhs = (int64_t(r.Y) - p.Y) * (int64_t(q.X) - p.X);
    return q.Y > p.Y ? lhs > rhs : lhs < rhs;
}

// D3D11.3 coverage of the centre of pixel (x, y) by triangle (a, b, c) in either winding: it
// lies strictly on the triangle's side of all three edges, or exactly on a top or left edge.
inline bool covers(const pipeline::WindowVertex& a, const pipeline::WindowVertex& b,
                   const pipeline::WindowVertex& c, int x, int y) {
    const int64_t px = pixel_centre(x), py = pixel_centre(y);
    const pipeline::WindowVertex* v[3] = {&a, &b, &c};
    for (int i = 0; i < 3; ++i) {
        const pipeline::WindowVertex &p = *v[i], &q = *v[(i + 1) % 3], &r = *v[(i + 2) % 3];
        const int64_t side_r = orient(p, q, r.X, r.Y), side = orient(p, q, px, py);
        if (side_r == 0) return false;  // zero area
        if (side == 0 ? !is_top_or_left(p, q, r) : (side > 0) != (side_r > 0)) return false;
    }
    return true;
}

// The setup's reduced edge function F_i at pixel (x, y), stepped from its value at the box
// corner as triangle_setup.h defines it (exact in int64).
inline int64_t edge_at(const pipeline::TriangleSetup& t, int i, int x, int y) {
    return t.f[i] + int64_t(t.dx[i]) * (y - t.miny) - int64_t(t.dy[i]) * (x - t.minx);
}
inline bool setup_covers(const pipeline::TriangleSetup& t, int x, int y) {
    return edge_at(t, 0, x, y) >= 0 && edge_at(t, 1, x, y) >= 0 && edge_at(t, 2, x, y) >= 0;
}

// A random snapped triangle whose vertices lie within `extent` pixels of a centre drawn from
// [-margin, width + margin] x [-margin, height + margin] (pixels), depths in [0, 1). Some
// triangles are put on the half-pixel grid, where edges run exactly through pixel centres and
// the fill rule decides, some get axis-aligned edges, and some have one depth at all three
// vertices (0.5, or 1.0 which the depth test LESS never passes), so that overlapping ones tie.
struct RandomTriangle {
    pipeline::WindowVertex v[3];
};
inline RandomTriangle random_triangle(Rng& rng, int width, int height, int extent, int margin = 0) {
    constexpr int64_t kLimit = int64_t(pipeline::kCoordLimit) * pipeline::kSubpixels;  // the guard band
    const int64_t cx = rng.uniform(-int64_t(margin) * 256, int64_t(width + margin) * 256);
    const int64_t cy = rng.uniform(-int64_t(margin) * 256, int64_t(height + margin) * 256);
    const int64_t r = int64_t(extent) * 256;
    const bool on_grid = rng.chance(30);
    RandomTriangle t;
    for (pipeline::WindowVertex& v : t.v) {
        int64_t x = std::clamp<int64_t>(cx + rng.uniform(-r, r), -kLimit, kLimit);
        int64_t y = std::clamp<int64_t>(cy + rng.uniform(-r, r), -kLimit, kLimit);
        if (on_grid) x &= ~int64_t(127), y &= ~int64_t(127);  // multiples of half a pixel
        v = {int32_t(x), int32_t(y), rng.unit()};
    }
    if (rng.chance(15)) t.v[1].Y = t.v[0].Y;  // a horizontal edge
    if (rng.chance(15)) t.v[2].X = t.v[1].X;  // a vertical edge
    if (rng.chance(10)) {
        const float z = rng.chance(70) ? 0.5f : 1.0f;
        for (pipeline::WindowVertex& v : t.v) v.z = z;
    }
    return t;
}

// `count` drawn setups of random triangles over `viewport`, each with a vertex extent drawn
// from `extents` (pixels; those beyond 1000 reach out to the guard band), ids in submission
// order.
inline std::vector<pipeline::TriangleSetup> random_setups(Rng& rng, const pipeline::Viewport& viewport, int count,
                                                          std::initializer_list<int> extents, int samples = 1) {
    std::vector<pipeline::TriangleSetup> setups;
    while (int(setups.size()) < count) {
        const int extent = extents.begin()[rng.uniform(0, int64_t(extents.size()) - 1)];
        const RandomTriangle tri = random_triangle(rng, viewport.width, viewport.height, extent, extent > 1000 ? 0 : 20);
        pipeline::TriangleSetup t;
        if (setup_triangle(tri.v[0], tri.v[1], tri.v[2], pipeline::CullMode::none, viewport, t, samples) !=
            pipeline::SetupResult::drawn)
            continue;
        t.triangle = uint32_t(setups.size());
        setups.push_back(t);
    }
    return setups;
}

}  // namespace tessera::test
