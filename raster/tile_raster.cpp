#include "raster/tile_raster.h"

#include <algorithm>
#include <bit>

namespace tessera {

namespace {

using simd::kLanes;
using simd::kStampH;
using simd::kStampW;
using simd::vfloat;
using simd::vint;
using simd::vmask;

constexpr int kBlock = 16;  // block edge for big triangles (int32-exact up to 64, fixed_point.h)

// One edge function in the lanes of a stamp: F at the stamp's corner pixel (scalar), the lane
// offsets F(corner + lane) - F(corner), and the steps between stamps.
struct EdgeLanes {
    int32_t f;
    int32_t step_x, step_y;  // per stamp
    vint offset;
};

EdgeLanes edge_lanes(int32_t f, int32_t dx, int32_t dy) {
    return {f, -dy * kStampW, dx * kStampH, simd::stamp_x() * vint(-dy) + simd::stamp_y() * vint(dx)};
}

// An edge that is inside over the whole region: F = 0 everywhere passes "F >= 0".
EdgeLanes accepted_edge() { return {0, 0, 0, vint(0)}; }

// Visits the stamps with corners (sx, sy), sx0 <= sx <= sx1, sy0 <= sy <= sy1 (stamp-aligned,
// frame coordinates): coverage from the three edges, depth from the plane. sink(index of the
// stamp in the tile buffers, corner x, corner y, coverage, depth).
template <class Sink>
inline void traverse_stamps(const DepthPlane& plane, EdgeLanes e0, EdgeLanes e1, EdgeLanes e2,
                            int sx0, int sy0, int sx1, int sy1, const TileRect& tile, int tile_size,
                            Sink&& sink) {
    const vfloat lane_x = simd::to_float(simd::stamp_x());
    const vfloat lane_y = simd::to_float(simd::stamp_y());
    const vfloat a(plane.a), b(plane.b), c(plane.c);
    const int stamps_per_row = tile_size / kStampW;
    for (int sy = sy0; sy <= sy1; sy += kStampH) {
        // DepthPlane::at: fma(a, x - ax, fma(b, y - ay, c)), x - ax and y - ay exact in float.
        const vfloat z_row = simd::fma(b, vfloat(float(sy - plane.ay)) + lane_y, c);
        int32_t f0 = e0.f, f1 = e1.f, f2 = e2.f;
        size_t index = (size_t((sy - tile.y0) / kStampH) * stamps_per_row + (sx0 - tile.x0) / kStampW) * kLanes;
        for (int sx = sx0; sx <= sx1; sx += kStampW, index += kLanes) {
            // Inside where all three F >= 0: one sign test on their bitwise OR.
            const vint any_negative = (vint(f0) + e0.offset) | (vint(f1) + e1.offset) | (vint(f2) + e2.offset);
            const vmask covered = any_negative >= vint(0);
            f0 += e0.step_x;
            f1 += e1.step_x;
            f2 += e2.step_x;
            if (!simd::any(covered)) continue;
            vfloat z = simd::fma(a, vfloat(float(sx - plane.ax)) + lane_x, z_row);
            z = simd::min(simd::max(z, vfloat(0.0f)), vfloat(1.0f));
            sink(index, sx, sy, covered, z);
        }
        e0.f += e0.step_y;
        e1.f += e1.step_y;
        e2.f += e2.step_y;
    }
}

// F_i at pixel (x, y), from the setup's value at (minx, miny); exact in int64.
int64_t edge_at(const TriangleSetup& t, int i, int x, int y) {
    return t.f[i] + int64_t(t.dx[i]) * (y - t.miny) - int64_t(t.dy[i]) * (x - t.minx);
}

// Traverses the part of triangle `t` inside `tile`, calling sink as traverse_stamps does.
template <class Sink>
inline void traverse(const TriangleSetup& t, const TileRect& tile, int tile_size, Sink&& sink) {
    const int x0 = std::max<int>(t.minx, tile.x0), x1 = std::min<int>(t.maxx, tile.x1 - 1);
    const int y0 = std::max<int>(t.miny, tile.y0), y1 = std::min<int>(t.maxy, tile.y1 - 1);
    if (x0 > x1 || y0 > y1) return;
    const int sx0 = x0 & ~(kStampW - 1), sy0 = y0 & ~(kStampH - 1);
    if (t.small) {
        // Small triangle: int32 lanes are exact anywhere near its box (fixed_point.h).
        traverse_stamps(t.depth, edge_lanes(int32_t(edge_at(t, 0, sx0, sy0)), t.dx[0], t.dy[0]),
                        edge_lanes(int32_t(edge_at(t, 1, sx0, sy0)), t.dx[1], t.dy[1]),
                        edge_lanes(int32_t(edge_at(t, 2, sx0, sy0)), t.dx[2], t.dy[2]), sx0, sy0, x1,
                        y1, tile, tile_size, sink);
        return;
    }
    // Big triangle: per 16x16 block, reject when an edge is negative over the whole block,
    // accept edges positive over it, and step the others in int32 from the block's corner.
    constexpr int64_t kSpan = kBlock - 1;
    for (int by = y0 & ~(kBlock - 1); by <= y1; by += kBlock) {
        for (int bx = x0 & ~(kBlock - 1); bx <= x1; bx += kBlock) {
            EdgeLanes lanes[3];
            bool rejected = false;
            const int px0 = std::max(bx, sx0), py0 = std::max(by, sy0);
            for (int i = 0; i < 3 && !rejected; ++i) {
                const int64_t f = edge_at(t, i, bx, by);
                const int64_t dx = t.dx[i], dy = t.dy[i];
                const int64_t lo = f + std::min<int64_t>(0, -dy) * kSpan + std::min<int64_t>(0, dx) * kSpan;
                const int64_t hi = f + std::max<int64_t>(0, -dy) * kSpan + std::max<int64_t>(0, dx) * kSpan;
                if (hi < 0) rejected = true;
                else if (lo >= 0) lanes[i] = accepted_edge();
                else lanes[i] = edge_lanes(int32_t(edge_at(t, i, px0, py0)), t.dx[i], t.dy[i]);
            }
            if (rejected) continue;
            traverse_stamps(t.depth, lanes[0], lanes[1], lanes[2], px0, py0,
                            std::min(bx + kBlock - 1, x1), std::min(by + kBlock - 1, y1), tile,
                            tile_size, sink);
        }
    }
}

}  // namespace

void TileBuffers::clear(int tile_size) {
    size = tile_size;
    const size_t n = size_t(tile_size) * size_t(tile_size);
    depth.resize(n);
    triangle.resize(n);
    const vfloat one(1.0f);
    const vint none(int32_t(0xFFFFFFFFu));
    for (size_t i = 0; i < n; i += kLanes) {
        one.store(&depth[i]);
        none.store(reinterpret_cast<int32_t*>(&triangle[i]));
    }
}

void rasterize_opaque(const TriangleSetup& t, const TileRect& tile, TileBuffers& buffers) {
    float* depth = buffers.depth.data();
    uint32_t* ids = buffers.triangle.data();
    const vint id(int32_t(t.triangle));
    traverse(t, tile, buffers.size, [&](size_t index, int, int, vmask covered, vfloat z) {
        const vmask pass = covered & (z < vfloat::load(depth + index));
        simd::store_masked(depth + index, pass, z);
        simd::store_masked(ids + index, pass, id);
    });
}

size_t rasterize_tested(const TriangleSetup& t, const TileRect& tile, const float* depth,
                        size_t stride, Fragment* out) {
    // Row-major depth, so lanes are tested one by one (transparency is the rare path).
    alignas(64) float z_lanes[kLanes];
    size_t n = 0;
    const int tile_size = 1 << 8;  // any stamp-aligned width works: indices are unused here
    traverse(t, tile, tile_size, [&](size_t, int sx, int sy, vmask covered, vfloat z) {
        z.store(z_lanes);
        for (uint32_t bits = simd::bits(covered); bits; bits &= bits - 1) {
            const int lane = std::countr_zero(bits);
            const int x = sx + lane % kStampW, y = sy + lane / kStampW;
            if (x >= tile.x1 || y >= tile.y1) continue;
            const float d = depth[size_t(y - tile.y0) * stride + (x - tile.x0)];
            if (z_lanes[lane] < d) out[n++] = {uint16_t(x), uint16_t(y), z_lanes[lane]};
        }
    });
    return n;
}

}  // namespace tessera
