// Triangle setup (raster/pipeline/triangle_setup.h) against exact arithmetic: the reduced edge
// functions against the int64 edge function at every pixel centre, the D3D11.3 top-left rule
// on shared edges and vertices (every pixel centre of a closed mesh covered exactly once),
// the pixel box, the depth plane against the exact plane, culling against the sign of the
// exact area, and the snap against the vertex stage.
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <map>
#include <utility>
#include <vector>

#include "pipeline_fixtures.h"
#include "raster/pipeline/triangle_setup_lanes.h"
#include "raster/pipeline/vertex_stage.h"

namespace tessera::pipeline {
namespace {

using test::covers;
using test::edge_at;
using test::is_top_or_left;
using test::orient;
using test::pixel_centre;
using test::random_triangle;
using test::RandomTriangle;
using test::Rng;
using test::setup_covers;

// floor(a / 256), written without shifts.
int64_t floor_div_256(int64_t a) { return (a - ((a % 256) + 256) % 256) / 256; }

// The three vertices in the order setup orients them (triangle_setup.h: edge i runs from vertex
// i to vertex i+1, inside where every edge function is positive).
std::array<WindowVertex, 3> oriented(const WindowVertex& v0, const WindowVertex& v1, const WindowVertex& v2) {
    if (orient(v0, v1, v2.X, v2.Y) > 0) return {v0, v1, v2};
    return {v0, v2, v1};
}

// Setup's F_i at pixel (x, y) equals floor((E_i - 1 + tl_i) / 256), E_i the exact edge function
// at the pixel centre and tl_i = 1 on a top or left edge (fixed_point.h): "F >= 0" is then
// exactly "E > 0, or E == 0 on a top or left edge".
void expect_exact_edges(const TriangleSetup& t, const std::array<WindowVertex, 3>& v, int x, int y) {
    for (int i = 0; i < 3; ++i) {
        const WindowVertex &p = v[i], &q = v[(i + 1) % 3], &r = v[(i + 2) % 3];
        const int64_t e = orient(p, q, pixel_centre(x), pixel_centre(y));
        const int64_t tl = is_top_or_left(p, q, r) ? 1 : 0;
        ASSERT_EQ(edge_at(t, i, x, y), floor_div_256(e - 1 + tl))
            << "edge " << i << " at pixel (" << x << ", " << y << ")";
    }
}

// Pixels x in [0, size) whose centre lies within [lo, hi] sub-pixels, as an inclusive range
// (empty when first > last).
std::pair<int, int> centres_within(int32_t lo, int32_t hi, int size) {
    int first = size, last = -1;
    for (int x = 0; x < size; ++x)
        if (lo <= pixel_centre(x) && pixel_centre(x) <= hi) first = std::min(first, x), last = x;
    return {first, last};
}

TEST(PipelineTriangleSetup, EdgeFunctionsAreTheExactEdgeFunctionAtEveryPixelCentre) {
    const int w = 160, h = 120;
    const Viewport viewport(w, h);
    Rng rng(16001);
    int drawn = 0, covered_pixels = 0;
    for (int n = 0; n < 1500; ++n) {
        const int extent = std::array{1, 3, 10, 40, 90}[n % 5];
        const test::RandomTriangle tri = test::random_triangle(rng, w, h, extent, 20);
        const WindowVertex &v0 = tri.v[0], &v1 = tri.v[1], &v2 = tri.v[2];
        TriangleSetup t;
        const SetupResult result = setup_triangle(v0, v1, v2, CullMode::none, viewport, t);
        if (orient(v0, v1, v2.X, v2.Y) == 0) {
            EXPECT_EQ(result, SetupResult::zero_area);
            continue;
        }
        // The box: the pixels whose centre lies within the vertices' box, inside the viewport.
        const auto [minx, maxx] = centres_within(std::min({v0.X, v1.X, v2.X}), std::max({v0.X, v1.X, v2.X}), w);
        const auto [miny, maxy] = centres_within(std::min({v0.Y, v1.Y, v2.Y}), std::max({v0.Y, v1.Y, v2.Y}), h);
        if (minx > maxx || miny > maxy) {
            EXPECT_EQ(result, SetupResult::no_samples);
            continue;
        }
        ASSERT_EQ(result, SetupResult::drawn);
        ++drawn;
        EXPECT_EQ(t.minx, minx);
        EXPECT_EQ(t.maxx, maxx);
        EXPECT_EQ(t.miny, miny);
        EXPECT_EQ(t.maxy, maxy);
        const auto v = oriented(v0, v1, v2);
        for (int i = 0; i < 3; ++i) {
            EXPECT_EQ(t.dx[i], v[(i + 1) % 3].X - v[i].X);
            EXPECT_EQ(t.dy[i], v[(i + 1) % 3].Y - v[i].Y);
        }
        // Exact over the box and a margin around it (the edge functions are affine; traversal
        // evaluates them on whole stamps that reach past the box).
        int covered = 0;
        for (int y = miny - 4; y <= maxy + 4; ++y)
            for (int x = minx - 4; x <= maxx + 4; ++x) {
                expect_exact_edges(t, v, x, y);
                if (HasFatalFailure()) return;
                const bool inside_box = x >= minx && x <= maxx && y >= miny && y <= maxy;
                const bool in_viewport = x >= 0 && x < w && y >= 0 && y < h;
                // Every covered pixel of the viewport is in the box.
                if (in_viewport && !inside_box) {
                    ASSERT_FALSE(covers(v0, v1, v2, x, y)) << x << ", " << y;
                }
                if (inside_box) {
                    ASSERT_EQ(setup_covers(t, x, y), covers(v0, v1, v2, x, y)) << x << ", " << y;
                    covered += setup_covers(t, x, y);
                }
            }
        covered_pixels += covered;
    }
    EXPECT_GT(drawn, 900);
    EXPECT_GT(covered_pixels, 100000);
}

// The largest coordinates the guard band lets through (|X|, |Y| up to 16000 pixels) on the
// largest viewport: the int64 ranges of fixed_point.h, checked at the box corners and random
// pixels of the box.
TEST(PipelineTriangleSetup, EdgeFunctionsStayExactAtTheCoordinateLimits) {
    const int size = kMaxViewport;
    const Viewport viewport(size, size);
    Rng rng(16002);
    int drawn = 0;
    for (int n = 0; n < 300; ++n) {
        const test::RandomTriangle tri = test::random_triangle(rng, size, size, 16000, 8000);
        TriangleSetup t;
        if (setup_triangle(tri.v[0], tri.v[1], tri.v[2], CullMode::none, viewport, t) != SetupResult::drawn)
            continue;
        ++drawn;
        const auto v = oriented(tri.v[0], tri.v[1], tri.v[2]);
        for (int k = 0; k < 200; ++k) {
            const int x = k < 4 ? (k & 1 ? t.maxx : t.minx) : int(rng.uniform(t.minx, t.maxx));
            const int y = k < 4 ? (k & 2 ? t.maxy : t.miny) : int(rng.uniform(t.miny, t.maxy));
            expect_exact_edges(t, v, x, y);
            if (HasFatalFailure()) return;
            ASSERT_EQ(setup_covers(t, x, y), covers(tri.v[0], tri.v[1], tri.v[2], x, y));
        }
    }
    EXPECT_GT(drawn, 150);
}

// A closed triangle mesh in window coordinates: the fill rule covers every pixel centre inside
// it exactly once, on shared edges and shared vertices too, and none twice anywhere.
struct WindowMesh {
    std::vector<WindowVertex> vertices;
    std::vector<std::array<int, 3>> triangles;
};

// Per-pixel count of the triangles of `mesh` whose setup covers the pixel.
std::vector<int> setup_coverage(const WindowMesh& mesh, const Viewport& viewport) {
    std::vector<int> count(size_t(viewport.width) * viewport.height, 0);
    for (const auto& tri : mesh.triangles) {
        TriangleSetup t;
        if (setup_triangle(mesh.vertices[tri[0]], mesh.vertices[tri[1]], mesh.vertices[tri[2]], CullMode::none,
                           viewport, t) != SetupResult::drawn)
            continue;
        for (int y = t.miny; y <= t.maxy; ++y)
            for (int x = t.minx; x <= t.maxx; ++x) count[size_t(y) * viewport.width + x] += setup_covers(t, x, y);
    }
    return count;
}

// Whether the centre of pixel (x, y) is inside `mesh`'s union and off its outer boundary (the
// edges that belong to one triangle only): such a centre is inside one triangle or on an edge
// or vertex shared by several, and must be covered exactly once.
bool strictly_inside(const WindowMesh& mesh, const std::vector<std::pair<int, int>>& boundary, int x, int y) {
    const int64_t px = pixel_centre(x), py = pixel_centre(y);
    for (const auto& [a, b] : boundary) {
        const WindowVertex &p = mesh.vertices[a], &q = mesh.vertices[b];
        if (orient(p, q, px, py) == 0 && std::min(p.X, q.X) <= px && px <= std::max(p.X, q.X) &&
            std::min(p.Y, q.Y) <= py && py <= std::max(p.Y, q.Y))
            return false;
    }
    for (const auto& tri : mesh.triangles) {
        const WindowVertex &a = mesh.vertices[tri[0]], &b = mesh.vertices[tri[1]], &c = mesh.vertices[tri[2]];
        const int64_t s = orient(a, b, c.X, c.Y) > 0 ? 1 : -1;
        if (s * orient(a, b, px, py) >= 0 && s * orient(b, c, px, py) >= 0 && s * orient(c, a, px, py) >= 0)
            return true;
    }
    return false;
}

void expect_covered_once(const WindowMesh& mesh, const Viewport& viewport, const char* what) {
    std::map<std::pair<int, int>, int> edges;
    for (const auto& tri : mesh.triangles)
        for (int i = 0; i < 3; ++i) ++edges[std::minmax(tri[i], tri[(i + 1) % 3])];
    std::vector<std::pair<int, int>> boundary;
    for (const auto& [edge, n] : edges)
        if (n == 1) boundary.push_back(edge);
    const std::vector<int> count = setup_coverage(mesh, viewport);
    int inside = 0;
    for (int y = 0; y < viewport.height; ++y)
        for (int x = 0; x < viewport.width; ++x) {
            const int c = count[size_t(y) * viewport.width + x];
            ASSERT_LE(c, 1) << what << ": pixel (" << x << ", " << y << ") covered twice";
            if (strictly_inside(mesh, boundary, x, y)) {
                ASSERT_EQ(c, 1) << what << ": pixel (" << x << ", " << y << ") inside the mesh not covered";
                ++inside;
            }
        }
    EXPECT_GT(inside, 100) << what;
}

// Quads of a cells_x x cells_y grid split along random diagonals, each triangle in a random
// winding. Vertex (i, j) is at (x0 + i * cell, y0 + j * cell) sub-pixels moved by up to
// `jitter`, then put on the lattice offset + k * snap. The quads stay convex while every
// vertex moves less than a quarter cell per axis: jitter + snap < cell / 4.
WindowMesh grid_mesh(Rng& rng, int cells_x, int cells_y, int32_t x0, int32_t y0, int32_t cell, int32_t jitter,
                     int32_t snap = 1, int32_t offset = 0) {
    WindowMesh m;
    auto coordinate = [&](int32_t base) {
        const int32_t c = base + int32_t(rng.uniform(-jitter, jitter));
        return c - (((c % snap) + snap) % snap) + offset;
    };
    for (int j = 0; j <= cells_y; ++j)
        for (int i = 0; i <= cells_x; ++i) m.vertices.push_back({coordinate(x0 + i * cell), coordinate(y0 + j * cell), 0.5f});
    auto id = [&](int i, int j) { return j * (cells_x + 1) + i; };
    auto add = [&](int a, int b, int c) {
        if (rng.chance(50)) std::swap(b, c);
        m.triangles.push_back({a, b, c});
    };
    for (int j = 0; j < cells_y; ++j)
        for (int i = 0; i < cells_x; ++i) {
            const int a = id(i, j), b = id(i + 1, j), c = id(i + 1, j + 1), d = id(i, j + 1);
            if (rng.chance(50)) add(a, b, c), add(a, c, d);
            else add(a, b, d), add(b, c, d);
        }
    return m;
}

// Edges through pixel centres, horizontal, vertical and diagonal: the outer boundary decides
// alone, so exactly the centres in [left, right) x [top, bottom) are covered, once each.
TEST(PipelineTriangleSetup, FillRuleCoversAnAlignedGridExactlyOnce) {
    const Viewport viewport(96, 80);
    Rng rng(16003);
    for (int32_t offset : {0, 128, 64}) {  // vertices on pixel corners, on centres, in between
        for (int32_t cell : {256, 3 * 256, 4 * 256, 512 + 128}) {
            const int32_t x0 = 5 * 256 + offset, y0 = 7 * 256 + offset;
            const int cells_x = 60 * 256 / cell, cells_y = 50 * 256 / cell;
            const WindowMesh m = grid_mesh(rng, cells_x, cells_y, x0, y0, cell, 0);
            const std::vector<int> count = setup_coverage(m, viewport);
            const int64_t x1 = x0 + int64_t(cells_x) * cell, y1 = y0 + int64_t(cells_y) * cell;
            for (int y = 0; y < viewport.height; ++y)
                for (int x = 0; x < viewport.width; ++x) {
                    const bool inside = x0 <= pixel_centre(x) && pixel_centre(x) < x1 && y0 <= pixel_centre(y) &&
                                        pixel_centre(y) < y1;
                    ASSERT_EQ(count[size_t(y) * viewport.width + x], inside ? 1 : 0)
                        << "offset " << offset << " cell " << cell << " pixel (" << x << ", " << y << ")";
                }
        }
    }
}

TEST(PipelineTriangleSetup, FillRuleCoversJitteredGridsExactlyOnce) {
    const Viewport viewport(120, 100);
    Rng rng(16004);
    struct Lattice {
        int32_t cell, jitter, snap, offset;
    };
    // Anywhere; on the half-pixel lattice (most edges and vertices meet pixel centres exactly);
    // on pixel centres; on pixel corners.
    for (const Lattice& l : {Lattice{768, 150, 1, 0}, Lattice{1869, 360, 1, 0}, Lattice{1536, 200, 128, 0},
                             Lattice{3072, 400, 256, 128}, Lattice{3072, 400, 256, 0}}) {
        const WindowMesh m = grid_mesh(rng, 100 * 256 / l.cell, 80 * 256 / l.cell, 6 * 256, 9 * 256, l.cell,
                                       l.jitter, l.snap, l.offset);
        expect_covered_once(m, viewport, "jittered grid");
        if (HasFatalFailure()) return;
    }
}

// Fans of triangles around one vertex, on a pixel centre or not: the shared vertex and the
// spokes through it are covered exactly once.
TEST(PipelineTriangleSetup, FillRuleCoversFansAroundASharedVertexExactlyOnce) {
    const Viewport viewport(80, 80);
    Rng rng(16005);
    for (int n = 0; n < 40; ++n) {
        WindowMesh m;
        const int32_t cx = 40 * 256 + (n % 2 ? 128 : int32_t(rng.uniform(0, 255)));
        m.vertices.push_back({cx, cx, 0.5f});
        const int spokes = 3 + n % 10;
        for (int k = 0; k < spokes; ++k) {
            // Axis-aligned spokes when spokes % 4 == 0 (angles at multiples of 90 degrees).
            const double angle = 2.0 * M_PI * (k + (spokes % 4 ? 0.3 * rng.unit() : 0.0)) / spokes;
            const double radius = 256.0 * (12.0 + 20.0 * rng.unit());
            m.vertices.push_back({cx + int32_t(std::lround(radius * std::cos(angle))),
                                  cx + int32_t(std::lround(radius * std::sin(angle))), 0.5f});
        }
        for (int k = 0; k < spokes; ++k) {
            int b = 1 + k, c = 1 + (k + 1) % spokes;
            if (rng.chance(50)) std::swap(b, c);
            m.triangles.push_back({0, b, c});
        }
        expect_covered_once(m, viewport, "fan");
        if (HasFatalFailure()) return;
        if (n % 2) {  // the centre vertex sits on pixel (40, 40)'s centre
            const std::vector<int> count = setup_coverage(m, viewport);
            EXPECT_EQ(count[size_t(40) * viewport.width + 40], 1);
        }
    }
}

// The four triangles around a pixel centre whose edges are exactly horizontal and vertical
// (the top-left cases one by one): the centre goes to the one triangle whose two edges through
// it are top or left.
TEST(PipelineTriangleSetup, TopLeftRuleGivesTheSharedCentreToOneTriangle) {
    const Viewport viewport(16, 16);
    const WindowVertex c{8 * 256 + 128, 8 * 256 + 128, 0.5f};
    const int32_t r = 4 * 256;
    const WindowVertex right{c.X + r, c.Y, 0.5f}, down{c.X, c.Y + r, 0.5f};
    const WindowVertex left{c.X - r, c.Y, 0.5f}, up{c.X, c.Y - r, 0.5f};
    // The quadrant right of and below the centre has its horizontal edge on top and its
    // vertical edge on the left: it alone covers the centre.
    struct Case {
        WindowVertex a, b;
        bool covers_centre;
    } cases[] = {{right, down, true}, {down, left, false}, {left, up, false}, {up, right, false}};
    for (const Case& k : cases)
        for (bool swap : {false, true}) {
            TriangleSetup t;
            const WindowVertex& b = swap ? k.b : k.a;
            const WindowVertex& d = swap ? k.a : k.b;
            ASSERT_EQ(setup_triangle(c, b, d, CullMode::none, viewport, t), SetupResult::drawn);
            EXPECT_EQ(setup_covers(t, 8, 8), k.covers_centre);
        }
}

// The depth plane against the plane through the snapped vertices evaluated exactly at each
// covered pixel centre (barycentrics from the int64 edge functions, the sum in long double),
// within the rounding of the float coefficients and the two fused multiply-adds.
TEST(PipelineTriangleSetup, DepthPlaneIsTheExactPlaneAtPixelCentres) {
    const int w = 160, h = 120;
    const Viewport viewport(w, h);
    Rng rng(16006);
    int checked = 0;
    for (int n = 0; n < 600; ++n) {
        const test::RandomTriangle tri = test::random_triangle(rng, w, h, std::array{2, 12, 60, 200}[n % 4], 40);
        const WindowVertex &v0 = tri.v[0], &v1 = tri.v[1], &v2 = tri.v[2];
        TriangleSetup t;
        if (setup_triangle(v0, v1, v2, CullMode::none, viewport, t) != SetupResult::drawn) continue;
        // Both windings give the same plane (a flat one may differ in the sign of a zero).
        const DepthPlane p = DepthPlane::from(v0, v1, v2), q = DepthPlane::from(v0, v2, v1);
        EXPECT_EQ(p.a, q.a);
        EXPECT_EQ(p.b, q.b);
        EXPECT_EQ(p.c, q.c);
        EXPECT_EQ(p.ax, v0.X >> 8);
        EXPECT_EQ(p.ay, v0.Y >> 8);
        const int64_t area = orient(v0, v1, v2.X, v2.Y);
        for (int y = t.miny; y <= t.maxy; ++y)
            for (int x = t.minx; x <= t.maxx; ++x) {
                if (!setup_covers(t, x, y)) continue;
                const int64_t px = pixel_centre(x), py = pixel_centre(y);
                const long double exact = (static_cast<long double>(orient(v1, v2, px, py)) * v0.z +
                                           static_cast<long double>(orient(v2, v0, px, py)) * v1.z +
                                           static_cast<long double>(orient(v0, v1, px, py)) * v2.z) /
                                          static_cast<long double>(area);
                const float dx = float(x - t.depth.ax), dy = float(y - t.depth.ay);
                const double bound = 4.0 * 0x1p-24 *
                                     (std::fabs(t.depth.a * dx) + std::fabs(t.depth.b * dy) + std::fabs(t.depth.c) + 1.0);
                ASSERT_NEAR(double(t.depth.at(x, y)), double(exact), bound) << "pixel (" << x << ", " << y << ")";
                ++checked;
            }
    }
    EXPECT_GT(checked, 100000);

    // Clamped to [0, 1] where the plane leaves it, and finite for a zero-area triangle.
    const WindowVertex a{0, 0, 0.0f}, b{10 * 256, 0, 1.0f}, c{0, 10 * 256, 0.5f};
    const DepthPlane steep = DepthPlane::from(a, b, c);
    EXPECT_EQ(steep.at(100, 0), 1.0f);
    EXPECT_EQ(steep.at(-100, 0), 0.0f);
    const DepthPlane flat = DepthPlane::from(a, a, c);
    EXPECT_EQ(flat.at(3, 4), 0.0f);
    EXPECT_EQ(DepthPlane::from(c, c, c).at(-7, 9), 0.5f);
}

// Front faces are counter-clockwise in NDC: triangles made in NDC with a known orientation,
// projected and snapped on a 256 x 256 viewport (NDC = X / 2^15 - 1, Y flipped, exact in
// double), culled against the sign of their exact area.
TEST(PipelineTriangleSetup, CullingFollowsTheSignOfTheExactArea) {
    const Viewport viewport(256, 256);
    Rng rng(16007);
    int front_faces = 0, back_faces = 0;
    for (int n = 0; n < 3000; ++n) {
        WindowVertex v[3];
        for (WindowVertex& p : v) {
            const glm::vec4 clip{2.0f * rng.unit() - 1.0f, 2.0f * rng.unit() - 1.0f, 2.0f * rng.unit() - 1.0f, 1.0f};
            p = project_and_snap(viewport, n % 7 == 0 ? glm::vec4(0.25f, -0.5f, 0.0f, 1.0f) : clip);
        }
        if (n % 11 == 0) v[2] = {2 * v[1].X - v[0].X, 2 * v[1].Y - v[0].Y, 0.5f};  // collinear
        auto ndc = [](const WindowVertex& p) {
            return glm::dvec2(double(p.X) / 32768.0 - 1.0, 1.0 - double(p.Y) / 32768.0);
        };
        const glm::dvec2 a = ndc(v[0]), b = ndc(v[1]), c = ndc(v[2]);
        const double ccw = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
        for (CullMode cull : {CullMode::none, CullMode::back, CullMode::front}) {
            TriangleSetup t;
            const SetupResult result = setup_triangle(v[0], v[1], v[2], cull, viewport, t);
            if (ccw == 0.0) {
                EXPECT_EQ(result, SetupResult::zero_area);
                continue;
            }
            const bool culled = (cull == CullMode::back && ccw < 0.0) || (cull == CullMode::front && ccw > 0.0);
            EXPECT_EQ(result == SetupResult::culled_face, culled) << "ccw " << ccw << " cull " << int(cull);
        }
        front_faces += ccw > 0.0;
        back_faces += ccw < 0.0;
    }
    EXPECT_GT(front_faces, 1000);
    EXPECT_GT(back_faces, 1000);
}

// Small (int32 traversal) exactly when the vertex box is under kSmallExtent sub-pixels.
TEST(PipelineTriangleSetup, SmallFlagFollowsTheVertexBox) {
    const Viewport viewport(1024, 1024);
    const WindowVertex o{100 * 256, 100 * 256, 0.5f};
    for (int32_t d : {kSmallExtent - 1, kSmallExtent}) {
        const WindowVertex wide{o.X + d, o.Y + 5 * 256, 0.5f}, tall{o.X + 5 * 256, o.Y + d, 0.5f};
        TriangleSetup t;
        ASSERT_EQ(setup_triangle(o, wide, {o.X, o.Y + 256, 0.5f}, CullMode::none, viewport, t), SetupResult::drawn);
        EXPECT_EQ(bool(t.small), d < kSmallExtent);
        ASSERT_EQ(setup_triangle(o, tall, {o.X + 256, o.Y, 0.5f}, CullMode::none, viewport, t), SetupResult::drawn);
        EXPECT_EQ(bool(t.small), d < kSmallExtent);
        EXPECT_EQ(t.transparent, 0);
    }
}

// setup_small_triangles gives setup_triangle's result and setup bit for bit on every small
// triangle, and hands the others back: random triangles of every size around kSmallExtent,
// across the viewport's edges and out to the guard band, on the half-pixel grid, degenerate,
// for every cull mode and with one and four samples.
TEST(PipelineTriangleSetup, LanesGiveTheScalarSetupBitForBit) {
    using simd::kLanes;
    const Viewport viewport(1000, 600);
    Rng rng(16009);
    size_t drawn = 0, small = 0, big = 0, on_edge = 0;
    for (int batch = 0; batch < 3000; ++batch) {
        const int extent = batch % 5 == 0 ? 127 + int(rng.uniform(0, 2)) : int(rng.uniform(1, 140));
        const int margin = batch % 7 == 0 ? 16000 : 40;
        RandomTriangle t[kLanes];
        alignas(64) int32_t X[3][kLanes], Y[3][kLanes];
        alignas(64) float z[3][kLanes];
        for (int lane = 0; lane < kLanes; ++lane) {
            t[lane] = random_triangle(rng, viewport.width, viewport.height, extent, margin);
            if (lane % 5 == 3) t[lane].v[2] = t[lane].v[1];  // zero area
            if (lane % 5 == 1)  // corners on pixel centres: edges through centres (on_edge)
                for (auto& v : t[lane].v) v.X = (v.X & ~(kSubpixels - 1)) | kSubpixels / 2, v.Y = (v.Y & ~(kSubpixels - 1)) | kSubpixels / 2;
            for (int k = 0; k < 3; ++k) X[k][lane] = t[lane].v[k].X, Y[k][lane] = t[lane].v[k].Y, z[k][lane] = t[lane].v[k].z;
        }
        WindowLanes w;
        for (int k = 0; k < 3; ++k) w.X[k] = simd::vint::load(X[k]), w.Y[k] = simd::vint::load(Y[k]), w.z[k] = simd::vfloat::load(z[k]);
        const uint32_t active = (uint32_t(rng.bits()) & ((1u << kLanes) - 1)) | 1u;
        simd::vmask mask = simd::lane_index() < simd::vint(0);
        for (int lane = 0; lane < kLanes; ++lane)
            if (active >> lane & 1) mask = mask | (simd::lane_index() == simd::vint(lane));
        const CullMode cull = CullMode(batch % 3);
        const int samples = batch % 4 == 1 ? 4 : 1;
        SmallSetups lanes;
        const uint32_t rest = simd::bits(setup_small_triangles(w, mask, cull, viewport, samples, lanes));
        ASSERT_EQ(rest & ~active, 0u);
        for (int lane = 0; lane < kLanes; ++lane) {
            if (!(active >> lane & 1)) continue;
            TriangleSetup scalar;
            const SetupResult expected = setup_triangle(t[lane].v[0], t[lane].v[1], t[lane].v[2], cull, viewport, scalar, samples);
            const int32_t w_extent = std::max({t[lane].v[0].X, t[lane].v[1].X, t[lane].v[2].X}) -
                                     std::min({t[lane].v[0].X, t[lane].v[1].X, t[lane].v[2].X});
            const int32_t h_extent = std::max({t[lane].v[0].Y, t[lane].v[1].Y, t[lane].v[2].Y}) -
                                     std::min({t[lane].v[0].Y, t[lane].v[1].Y, t[lane].v[2].Y});
            const bool is_small = w_extent < kSmallExtent && h_extent < kSmallExtent;
            ASSERT_EQ(bool(rest >> lane & 1), !is_small) << w_extent << " x " << h_extent;
            if (!is_small) {
                ++big;
                continue;
            }
            ++small;
            ASSERT_EQ(lanes.result[lane], expected) << "batch " << batch << " lane " << lane;
            if (expected != SetupResult::drawn) continue;
            ++drawn;
            TriangleSetup set_up;
            lanes.write(lane, set_up);
            scalar.triangle = set_up.triangle = 0;
            ASSERT_EQ(std::memcmp(&scalar, &set_up, offsetof(TriangleSetup, triangle)), 0) << "batch " << batch;
            ASSERT_EQ(scalar.small, set_up.small);
            ASSERT_EQ(scalar.transparent, set_up.transparent);
            ASSERT_EQ(scalar.on_edge, set_up.on_edge) << "batch " << batch << " lane " << lane;
            on_edge += scalar.on_edge != 0;
            for (int i = 0; i < 3; ++i) ASSERT_EQ(scalar.residue[i], set_up.residue[i]);
        }
    }
    EXPECT_GT(drawn, 5000u);
    EXPECT_GT(on_edge, 500u);
    EXPECT_GT(big, 1000u);
    EXPECT_GT(small, big);
}

// project_and_snap rounds to nearest, ties to even, and gives the vertex stage's bits.
TEST(PipelineTriangleSetup, SnapRoundsToNearestEvenLikeTheVertexStage) {
    const Viewport viewport(64, 64);  // window x = (ndc + 1) * 32: ndc steps of 2^-13 are 1/256 pixel
    for (const auto& [ndc_x, expected] : std::vector<std::pair<double, int32_t>>{
             {-1.0, 0}, {-1.0 + 0.5 * 0x1p-13, 0}, {-1.0 + 1.5 * 0x1p-13, 2}, {-1.0 + 2.5 * 0x1p-13, 2},
             {-1.0 + 0.75 * 0x1p-13, 1}, {0.0, 32 * 256}, {1.0, 64 * 256}}) {
        const WindowVertex v = project_and_snap(viewport, {float(ndc_x), 0.0f, 0.0f, 1.0f});
        EXPECT_EQ(v.X, expected) << ndc_x;
        EXPECT_EQ(v.Y, 32 * 256);
        EXPECT_EQ(v.z, 0.5f);
    }

    Mesh mesh;
    Rng rng(16008);
    for (int i = 0; i < 4000; ++i)
        mesh.positions.push_back({4.0f * rng.unit() - 2.0f, 4.0f * rng.unit() - 2.0f, -8.0f * rng.unit()});
    const glm::mat4 vp = glm::perspective(1.0f, 1.3f, 0.5f, 20.0f) *
                         glm::lookAt(glm::vec3(0.3f, 0.2f, 3.0f), glm::vec3(0.0f, 0.0f, -2.0f), glm::vec3(0, 1, 0));
    const Viewport large(1021, 767);
    ClipVertices out;
    run_vertex_stage(mesh, vp, large, out);
    int projected = 0;
    for (size_t i = 0; i < out.size(); ++i) {
        if (out.projected[i].code != 0) continue;
        const WindowVertex v = project_and_snap(large, out.clip(i));
        EXPECT_EQ(v.X, out.projected[i].window.X);
        EXPECT_EQ(v.Y, out.projected[i].window.Y);
        EXPECT_EQ(std::bit_cast<uint32_t>(v.z), std::bit_cast<uint32_t>(out.projected[i].window.z));
        ++projected;
    }
    EXPECT_GT(projected, 2000);
}

}  // namespace
}  // namespace tessera::pipeline
