#include "raster/pipeline/tile_raster.h"

#include <algorithm>
#include <bit>
#include <cstring>
#include <span>

#include "raster/core/visibility.h"

namespace tessera::pipeline {

namespace {

using simd::kLanes;
using simd::kStampH;
using simd::kStampW;
using simd::vfloat;
using simd::vint;
using simd::vmask;

constexpr int kBlock = 16;  // block edge for big triangles (int32-exact up to 64, fixed_point.h)
constexpr int kTinyExtent = 32;  // pixels: a small triangle's region under this is visited branch-free

// A value the reduced edge function F never takes (|F| < 2^25 in int32 lanes, fixed_point.h).
constexpr int32_t kNever = INT32_MIN;

// One edge function in the lanes of a stamp: F at the stamp's corner pixel (scalar), the lane
// offsets F(corner + lane) - F(corner), and the steps between stamps.
struct EdgeLanes {
    int32_t f;
    int32_t step_x, step_y;  // per stamp
    vint offset;
    bool accepted;  // inside over the whole region, at every sample
};

// For a triangle whose edges may run through pixel centres (holds_centres()): per edge, the F
// at which a lane lies exactly on it (0, or kNever for an edge that holds none or is accepted
// over the region) and its depth step (DepthPlane::edge_step()).
struct OnEdge {
    int32_t f[3];
    float step[3];
};

EdgeLanes edge_lanes(int32_t f, int32_t dx, int32_t dy) {
    return {f, -dy * kStampW, dx * kStampH, simd::stamp_x() * vint(-dy) + simd::stamp_y() * vint(dx), false};
}

// An edge that is inside over the whole region: F = 0 everywhere passes "F >= 0".
EdgeLanes accepted_edge() { return {0, 0, 0, vint(0), true}; }


// Visits the stamps with corners (sx, sy), sx0 <= sx <= sx1, sy0 <= sy <= sy1 (stamp-aligned,
// frame coordinates): coverage from the three edges, depth offset from the plane (with
// kOnEdge, plus the edge's step where a lane lies exactly on it: depth_offset()). sink(index
// of the stamp in the tile buffers, corner x, corner y, coverage, depth offset).
//
// kBranchless: the sink also gets stamps with no coverage (its masked stores then write
// nothing), and rows are not left early. For the few stamps of a small region this is
// faster than predicting "any lane covered" and the row exits, which mispredict often
// (sphere grid at 1080p, 1 thread, CPU time per frame: 16k triangles 3.4 -> 2.4 ms, 100k
// 8.2 -> 5.9 ms; regions up to 16 pixels gave 3.2 and 6.0 ms, up to 64 the same as 32).
template <bool kBranchless, bool kOnEdge, class Sink>
inline void traverse_stamps(const DepthPlane& plane, const EdgeLanes (&e)[3], const OnEdge* on, int sx0, int sy0,
                            int sx1, int sy1, const TileRect& tile, int tile_size, Sink&& sink) {
    const vfloat lane_x = simd::to_float(simd::stamp_x());
    const vfloat lane_y = simd::to_float(simd::stamp_y());
    const vfloat a(plane.a), b(plane.b), c(plane.c);
    // Edge values of the stamp row's first stamp, stepped with vector adds.
    vint row0 = vint(e[0].f) + e[0].offset, row1 = vint(e[1].f) + e[1].offset, row2 = vint(e[2].f) + e[2].offset;
    const vint step_x0(e[0].step_x), step_x1(e[1].step_x), step_x2(e[2].step_x);
    const vint step_y0(e[0].step_y), step_y1(e[1].step_y), step_y2(e[2].step_y);
    // An edge whose F does not grow to the right (step_x <= 0) that is negative over a whole
    // stamp stays negative for the rest of the row: leave the row there.
    const bool exit0 = e[0].step_x <= 0, exit1 = e[1].step_x <= 0, exit2 = e[2].step_x <= 0;
    const vint zero(0);
    const unsigned stamps_per_row = unsigned(tile_size / kStampW);
    for (int sy = sy0; sy <= sy1; sy += kStampH) {
        // DepthPlane::offset_at: fma(a, x - ax, fma(b, y - ay, c)), x - ax and y - ay exact in float.
        const vfloat z_row = simd::fma(b, vfloat(float(sy - plane.ay)) + lane_y, c);
        vint f0 = row0, f1 = row1, f2 = row2;
        float fx = float(sx0 - plane.ax);
        size_t index = (unsigned(sy - tile.y0) / kStampH * stamps_per_row + unsigned(sx0 - tile.x0) / kStampW) * kLanes;
        for (int sx = sx0; sx <= sx1; sx += kStampW, index += kLanes, fx += float(kStampW)) {
            // Inside where all three F >= 0: one sign test on their bitwise OR.
            const vmask covered = (f0 | f1 | f2) >= zero;
            if (kBranchless || simd::any(covered)) {
                vfloat z = simd::fma(a, vfloat(fx) + lane_x, z_row);
                if constexpr (kOnEdge) {
                    z = simd::select(f0 == vint(on->f[0]), z + vfloat(on->step[0]), z);
                    z = simd::select(f1 == vint(on->f[1]), z + vfloat(on->step[1]), z);
                    z = simd::select(f2 == vint(on->f[2]), z + vfloat(on->step[2]), z);
                }
                z = simd::min(simd::max(z, vfloat(-1.0f)), vfloat(0.0f));
                sink(index, sx, sy, covered, z);
            } else if ((exit0 && !simd::any(f0 >= zero)) || (exit1 && !simd::any(f1 >= zero)) ||
                       (exit2 && !simd::any(f2 >= zero))) {
                break;
            }
            f0 = f0 + step_x0;
            f1 = f1 + step_x1;
            f2 = f2 + step_x2;
        }
        row0 = row0 + step_y0;
        row1 = row1 + step_y1;
        row2 = row2 + step_y2;
    }
}

// The stamps of a region entirely inside the triangle: every lane covered, depth only.
template <class Sink>
inline void fill_stamps(const DepthPlane& plane, int sx0, int sy0, int sx1, int sy1, const TileRect& tile,
                        int tile_size, Sink&& sink) {
    const vfloat lane_x = simd::to_float(simd::stamp_x());
    const vfloat lane_y = simd::to_float(simd::stamp_y());
    const vfloat a(plane.a), b(plane.b), c(plane.c);
    const vmask all(true);
    const unsigned stamps_per_row = unsigned(tile_size / kStampW);
    for (int sy = sy0; sy <= sy1; sy += kStampH) {
        const vfloat z_row = simd::fma(b, vfloat(float(sy - plane.ay)) + lane_y, c);
        float fx = float(sx0 - plane.ax);
        size_t index = (unsigned(sy - tile.y0) / kStampH * stamps_per_row + unsigned(sx0 - tile.x0) / kStampW) * kLanes;
        for (int sx = sx0; sx <= sx1; sx += kStampW, index += kLanes, fx += float(kStampW)) {
            vfloat z = simd::fma(a, vfloat(fx) + lane_x, z_row);
            z = simd::min(simd::max(z, vfloat(-1.0f)), vfloat(0.0f));
            sink(index, sx, sy, all, z);
        }
    }
}

// The samples of a multisampled render as traversal uses them for one triangle: per sample
// and edge the exact change of F from the pixel centre (sample_offset()), their range per
// edge, and the sample's position in pixels from the centre (for the depth plane).
struct SampleLanes {
    int count = 0;
    int32_t offset[3][kMaxSamples];
    int32_t lo[3], hi[3];
    float ox[kMaxSamples], oy[kMaxSamples];
    // Per edge and sample: the F (before the sample's offset) at which the sample lies exactly
    // on the edge, -offset, when such samples exist (holds_sample()), else kNever; and the
    // edge's depth step. edge_holds: bit i when edge i has any.
    int32_t on_edge[3][kMaxSamples];
    float step[3];
    unsigned edge_holds = 0;

    SampleLanes(const TriangleSetup& t, std::span<const SampleOffset> pattern) : count(int(pattern.size())) {
        for (int i = 0; i < 3; ++i) {
            lo[i] = hi[i] = sample_offset(t, i, pattern[0].x, pattern[0].y);
            const bool top_left = is_top_left(t.dx[i], t.dy[i]);
            for (int s = 0; s < count; ++s) {
                offset[i][s] = sample_offset(t, i, pattern[s].x, pattern[s].y);
                lo[i] = std::min(lo[i], offset[i][s]);
                hi[i] = std::max(hi[i], offset[i][s]);
                // holds_sample()'s first two tests inline (a top-left edge whose sample step is
                // a whole number of F units: rare), which skip the call for almost every edge.
                const bool maybe = top_left && sample_step_is_whole(t, i, pattern[s].x, pattern[s].y);
                const bool holds = maybe && holds_sample(t, i, pattern[s].x, pattern[s].y);
                on_edge[i][s] = holds ? -offset[i][s] : kNever;
                edge_holds |= unsigned(holds) << i;
            }
            step[i] = (edge_holds >> i) & 1 ? t.depth.edge_step(t.dx[i], t.dy[i]) : 0.0f;
        }
        for (int s = 0; s < count; ++s) {
            ox[s] = float(pattern[s].x) * (1.0f / 16.0f);
            oy[s] = float(pattern[s].y) * (1.0f / 16.0f);
        }
    }
};

// traverse_stamps for several samples per pixel: coverage per sample from the edge values
// moved by the sample's offsets, depth offset from the plane at the sample (with kOnEdge, plus
// the edge's step where the sample lies exactly on it: depth_offset_at_sample()). sink(index
// of the stamp, corner x, corner y, sample, coverage, depth offset) per sample of a stamp with
// any coverage.
template <bool kBranchless, bool kOnEdge, class Sink>
inline void traverse_sample_stamps(const DepthPlane& plane, const EdgeLanes (&e)[3], const SampleLanes& samples,
                                   int sx0, int sy0, int sx1, int sy1, const TileRect& tile, int tile_size,
                                   Sink&& sink) {
    const vfloat lane_x = simd::to_float(simd::stamp_x());
    const vfloat lane_y = simd::to_float(simd::stamp_y());
    const vfloat a(plane.a), b(plane.b), c(plane.c);
    const int n = samples.count;
    vint row0 = vint(e[0].f) + e[0].offset, row1 = vint(e[1].f) + e[1].offset, row2 = vint(e[2].f) + e[2].offset;
    const vint step_x0(e[0].step_x), step_x1(e[1].step_x), step_x2(e[2].step_x);
    const vint step_y0(e[0].step_y), step_y1(e[1].step_y), step_y2(e[2].step_y);
    const bool exit0 = e[0].step_x <= 0, exit1 = e[1].step_x <= 0, exit2 = e[2].step_x <= 0;
    // An accepted edge (F = 0 everywhere) stays accepted at every sample: no offsets.
    const bool accepted[3] = {e[0].accepted, e[1].accepted, e[2].accepted};
    const vint hi0(accepted[0] ? 0 : samples.hi[0]), hi1(accepted[1] ? 0 : samples.hi[1]),
        hi2(accepted[2] ? 0 : samples.hi[2]);
    // Pointers, not a copy: a per-triangle copy of the offsets compiled to `rep movs`, whose
    // start-up cost was most of a sub-pixel triangle's traversal.
    static constexpr int32_t kNoOffsets[kMaxSamples] = {};
    const int32_t* off[3] = {accepted[0] ? kNoOffsets : samples.offset[0], accepted[1] ? kNoOffsets : samples.offset[1],
                             accepted[2] ? kNoOffsets : samples.offset[2]};
    const vint zero(0);
    const unsigned stamps_per_row = unsigned(tile_size / kStampW);
    for (int sy = sy0; sy <= sy1; sy += kStampH) {
        const vfloat y_row = vfloat(float(sy - plane.ay)) + lane_y;
        vint f0 = row0, f1 = row1, f2 = row2;
        float fx = float(sx0 - plane.ax);
        size_t index = (unsigned(sy - tile.y0) / kStampH * stamps_per_row + unsigned(sx0 - tile.x0) / kStampW) * kLanes;
        for (int sx = sx0; sx <= sx1; sx += kStampW, index += kLanes, fx += float(kStampW)) {
            vmask covered[kMaxSamples];
            vmask any_covered(false);
            for (int s = 0; s < n; ++s) {
                covered[s] = ((f0 + vint(off[0][s])) | (f1 + vint(off[1][s])) | (f2 + vint(off[2][s]))) >= zero;
                any_covered = any_covered | covered[s];
            }
            if (kBranchless || simd::any(any_covered)) {
                const vfloat x = vfloat(fx) + lane_x;
                for (int s = 0; s < n; ++s) {
                    // DepthPlane::at_sample: x - ax + ox, y - ay + oy, exact in float.
                    vfloat z = simd::fma(a, x + vfloat(samples.ox[s]), simd::fma(b, y_row + vfloat(samples.oy[s]), c));
                    if constexpr (kOnEdge) {
                        // An accepted edge is never one with samples on it (traverse()).
                        z = simd::select(f0 == vint(samples.on_edge[0][s]), z + vfloat(samples.step[0]), z);
                        z = simd::select(f1 == vint(samples.on_edge[1][s]), z + vfloat(samples.step[1]), z);
                        z = simd::select(f2 == vint(samples.on_edge[2][s]), z + vfloat(samples.step[2]), z);
                    }
                    z = simd::min(simd::max(z, vfloat(-1.0f)), vfloat(0.0f));
                    sink(index, sx, sy, s, covered[s], z);
                }
            } else if ((exit0 && !simd::any((f0 + hi0) >= zero)) || (exit1 && !simd::any((f1 + hi1) >= zero)) ||
                       (exit2 && !simd::any((f2 + hi2) >= zero))) {
                break;
            }
            f0 = f0 + step_x0;
            f1 = f1 + step_x1;
            f2 = f2 + step_x2;
        }
        row0 = row0 + step_y0;
        row1 = row1 + step_y1;
        row2 = row2 + step_y2;
    }
}

// fill_stamps for several samples per pixel: every sample covered, depth per sample.
template <class Sink>
inline void fill_sample_stamps(const DepthPlane& plane, const SampleLanes& samples, int sx0, int sy0, int sx1,
                               int sy1, const TileRect& tile, int tile_size, Sink&& sink) {
    const vfloat lane_x = simd::to_float(simd::stamp_x());
    const vfloat lane_y = simd::to_float(simd::stamp_y());
    const vfloat a(plane.a), b(plane.b), c(plane.c);
    const vmask all(true);
    const unsigned stamps_per_row = unsigned(tile_size / kStampW);
    for (int sy = sy0; sy <= sy1; sy += kStampH) {
        const vfloat y_row = vfloat(float(sy - plane.ay)) + lane_y;
        float fx = float(sx0 - plane.ax);
        size_t index = (unsigned(sy - tile.y0) / kStampH * stamps_per_row + unsigned(sx0 - tile.x0) / kStampW) * kLanes;
        for (int sx = sx0; sx <= sx1; sx += kStampW, index += kLanes, fx += float(kStampW)) {
            const vfloat x = vfloat(fx) + lane_x;
            for (int s = 0; s < samples.count; ++s) {
                vfloat z = simd::fma(a, x + vfloat(samples.ox[s]), simd::fma(b, y_row + vfloat(samples.oy[s]), c));
                z = simd::min(simd::max(z, vfloat(-1.0f)), vfloat(0.0f));
                sink(index, sx, sy, s, all, z);
            }
        }
    }
}

// F_i at pixel (x, y), from the setup's value at (minx, miny); exact in int64.
int64_t edge_at(const TriangleSetup& t, int i, int x, int y) {
    return t.f[i] + int64_t(t.dx[i]) * (y - t.miny) - int64_t(t.dy[i]) * (x - t.minx);
}

// Traverses the part of triangle `t` inside `tile`, calling sink as traverse_stamps does, or,
// with `samples` (multisampling), as traverse_sample_stamps does. kOnEdge: some edge of `t`
// may hold samples exactly (holds_centres(), holds_sample(); rare), whose lanes read the depth
// step there and on which a block is accepted whole only where F > 0.
template <bool kMulti, bool kOnEdge, class Sink>
inline void traverse_with(const TriangleSetup& t, const TileRect& tile, int tile_size, const SampleLanes* samples,
                          Sink&& sink) {
    const int x0 = std::max<int>(t.minx, tile.x0), x1 = std::min<int>(t.maxx, tile.x1 - 1);
    const int y0 = std::max<int>(t.miny, tile.y0), y1 = std::min<int>(t.maxy, tile.y1 - 1);
    if (x0 > x1 || y0 > y1) return;
    const int sx0 = x0 & ~(kStampW - 1), sy0 = y0 & ~(kStampH - 1);
    const unsigned holds = kOnEdge ? (kMulti ? samples->edge_holds : t.on_edge) : 0u;
    const auto partial = [&]<bool kBranchless>(const EdgeLanes (&lanes)[3], int px0, int py0, int px1, int py1) {
        if constexpr (kMulti) {
            traverse_sample_stamps<kBranchless, kOnEdge>(t.depth, lanes, *samples, px0, py0, px1, py1, tile,
                                                         tile_size, sink);
        } else if constexpr (kOnEdge) {
            OnEdge on;
            for (int i = 0; i < 3; ++i) {
                const bool here = (holds >> i) & 1 && !lanes[i].accepted;
                on.f[i] = here ? 0 : kNever;
                on.step[i] = here ? t.depth.edge_step(t.dx[i], t.dy[i]) : 0.0f;
            }
            traverse_stamps<kBranchless, true>(t.depth, lanes, &on, px0, py0, px1, py1, tile, tile_size, sink);
        } else {
            traverse_stamps<kBranchless, false>(t.depth, lanes, nullptr, px0, py0, px1, py1, tile, tile_size, sink);
        }
    };
    if (t.small) {
        // Small triangle: int32 is exact anywhere within a few pixels of its box, F at
        // (minx, miny) included (fixed_point.h).
        EdgeLanes lanes[3];
        for (int i = 0; i < 3; ++i)
            lanes[i] = edge_lanes(int32_t(t.f[i]) + t.dx[i] * (sy0 - t.miny) - t.dy[i] * (sx0 - t.minx), t.dx[i], t.dy[i]);
        if (x1 - sx0 < kTinyExtent && y1 - sy0 < kTinyExtent)
            partial.template operator()<true>(lanes, sx0, sy0, x1, y1);
        else
            partial.template operator()<false>(lanes, sx0, sy0, x1, y1);
        return;
    }
    // Big triangle: per 16x16 block, reject when an edge is negative over the whole block,
    // accept edges positive over it, and step the others in int32 from the block's corner.
    // With samples, the range of an edge over the block widens by its sample offsets.
    constexpr int64_t kSpan = kBlock - 1;
    for (int by = y0 & ~(kBlock - 1); by <= y1; by += kBlock) {
        for (int bx = x0 & ~(kBlock - 1); bx <= x1; bx += kBlock) {
            EdgeLanes lanes[3];
            bool full[3] = {false, false, false};
            bool rejected = false;
            const int px0 = std::max(bx, sx0), py0 = std::max(by, sy0);
            for (int i = 0; i < 3 && !rejected; ++i) {
                const int64_t f = edge_at(t, i, bx, by);
                const int64_t dx = t.dx[i], dy = t.dy[i];
                const int64_t lo = f + std::min<int64_t>(0, -dy) * kSpan + std::min<int64_t>(0, dx) * kSpan +
                                   (kMulti ? samples->lo[i] : 0);
                const int64_t hi = f + std::max<int64_t>(0, -dy) * kSpan + std::max<int64_t>(0, dx) * kSpan +
                                   (kMulti ? samples->hi[i] : 0);
                if (hi < 0) rejected = true;
                else if (lo >= (kOnEdge && (holds >> i) & 1 ? 1 : 0)) lanes[i] = accepted_edge(), full[i] = true;
                else lanes[i] = edge_lanes(int32_t(edge_at(t, i, px0, py0)), t.dx[i], t.dy[i]);
            }
            if (rejected) continue;
            const int bx1 = std::min(bx + kBlock - 1, x1), by1 = std::min(by + kBlock - 1, y1);
            if (full[0] && full[1] && full[2]) {  // inside the triangle: depth only
                if constexpr (kMulti) fill_sample_stamps(t.depth, *samples, px0, py0, bx1, by1, tile, tile_size, sink);
                else fill_stamps(t.depth, px0, py0, bx1, by1, tile, tile_size, sink);
                continue;
            }
            // A partial block (16x16 pixels at most) is walked branch-free, as a small region (BM_FillRate
            // at 250 px legs, 1 thread: 0.94x the CPU time of the row walk).
            partial.template operator()<true>(lanes, px0, py0, bx1, by1);
        }
    }
}

template <bool kMulti, class Sink>
inline void traverse(const TriangleSetup& t, const TileRect& tile, int tile_size, const SampleLanes* samples,
                     Sink&& sink) {
    if ((kMulti ? samples->edge_holds : t.on_edge) != 0)
        traverse_with<kMulti, true>(t, tile, tile_size, samples, sink);
    else
        traverse_with<kMulti, false>(t, tile, tile_size, samples, sink);
}

}  // namespace

void TileBuffers::clear(int tile_size, int sample_count) {
    size = tile_size;
    samples = sample_count;
    const size_t n = size_t(tile_size) * size_t(tile_size) * size_t(sample_count);
    depth.resize(n);
    triangle.resize(n);
    const vint none(int32_t(0xFFFFFFFFu));
    for (size_t i = 0; i < n; i += kLanes) {
        vfloat(0.0f).store(&depth[i]);  // depth offset of the far plane
        none.store(reinterpret_cast<int32_t*>(&triangle[i]));
    }
}

namespace {

// One array of a tile (stamp layout, `size` pixels a side) to row-major `out`, kStampH rows
// at a time through `rows_buffer` (kStampH x size values). Every group of stamps is reset to
// `empty` as it is read (the data is in L1 then: cheaper than a separate clear pass). With
// kDepth the values are depth offsets and leave as window depth (window_depth()).
template <bool kDepth>
void flush_rows(uint32_t* tile, int size, int width, int height, uint32_t* out, size_t stride,
                uint32_t empty, bool stream, uint32_t* rows_buffer) {
    const size_t stamps_per_row = size_t(size / kStampW);
    const vint cleared{int32_t(empty)};
    for (int y = 0; y < height; y += kStampH) {
        uint32_t* stamps = tile + size_t(y / kStampH) * stamps_per_row * kLanes;
        // kStampH stamps side by side are kLanes pixels wide: the unit store_stamp_rows moves.
        for (int x = 0; x < size; x += kLanes) {
            int32_t* group = reinterpret_cast<int32_t*>(stamps + size_t(x / kStampW) * kLanes);
            simd::store_stamp_rows(reinterpret_cast<uint32_t*>(group), rows_buffer + x, size_t(size), kStampH);
            for (int s = 0; s < kStampH; ++s) cleared.store(group + s * kLanes);
        }
        if constexpr (kDepth) {
            float* rows = reinterpret_cast<float*>(rows_buffer);
            for (size_t i = 0; i < size_t(kStampH) * size_t(size); i += kLanes)
                (vfloat::load(rows + i) + vfloat(1.0f)).store(rows + i);  // window_depth()
        }
        const int rows = std::min(kStampH, height - y);
        for (int r = 0; r < rows; ++r) {
            uint32_t* dst = out + size_t(y + r) * stride;
            const uint32_t* src = rows_buffer + size_t(r) * size_t(size);
            if (stream) simd::stream_copy(dst, src, size_t(width));
            else std::memcpy(dst, src, size_t(width) * sizeof(uint32_t));
        }
    }
}

}  // namespace

void TileBuffers::flush(int width, int height, uint32_t* triangle_out, float* depth_out,
                        size_t stride, bool stream) {
    rows.resize(size_t(kStampH) * size_t(size));
    // Non-temporal stores only pay on whole, aligned lines (a partial line is read first,
    // and misaligned streaming measured 1.6x slower than ordinary stores): stream only when
    // every row of the tile starts on a cache line.
    constexpr size_t kLine = 64 / sizeof(uint32_t);
    stream = stream && stride % kLine == 0 && reinterpret_cast<uintptr_t>(triangle_out) % 64 == 0 &&
             reinterpret_cast<uintptr_t>(depth_out) % 64 == 0;
    // One array after the other: interleaving the two doubles the write streams in flight,
    // which measured 2x slower than two sequential passes.
    if (triangle_out)
        flush_rows<false>(triangle.data(), size, width, height, triangle_out, stride, kNoTriangle, stream, rows.data());
    flush_rows<true>(reinterpret_cast<uint32_t*>(depth.data()), size, width, height,
                     reinterpret_cast<uint32_t*>(depth_out), stride, std::bit_cast<uint32_t>(0.0f), stream,
                     rows.data());
    if (stream) simd::stream_fence();
    // A partial tile leaves stamp rows below `height` uncopied and uncleared (and traversal
    // may have covered lanes past the viewport's edge): clear it all.
    if (width < size || height < size) clear(size, samples);
}

void TileBuffers::flush_planes(int width, int height, uint32_t* triangle_out, float* depth_out) {
    rows.resize(size_t(kStampH) * size_t(size));
    const size_t area = size_t(width) * size_t(height);
    for (int s = 0; s < samples; ++s) {
        flush_rows<false>(triangle.data() + size_t(s) * plane(), size, width, height, triangle_out + size_t(s) * area,
                          size_t(width), kNoTriangle, false, rows.data());
        flush_rows<true>(reinterpret_cast<uint32_t*>(depth.data() + size_t(s) * plane()), size, width, height,
                         reinterpret_cast<uint32_t*>(depth_out + size_t(s) * area), size_t(width),
                         std::bit_cast<uint32_t>(0.0f), false, rows.data());
    }
    if (width < size || height < size) clear(size, samples);  // as flush()
}

uint64_t TileBuffers::covered_pixels(int width, int height) const {
    uint64_t n = 0;
    const vint none{int32_t(kNoTriangle)};
    for (int sy = 0; sy < height; sy += kStampH)
        for (int sx = 0; sx < width; sx += kStampW) {
            vmask inside(true);
            if (sx + kStampW > width || sy + kStampH > height)
                inside = (vint(sx) + simd::stamp_x() < vint(width)) & (vint(sy) + simd::stamp_y() < vint(height));
            const vint ids = vint::load(reinterpret_cast<const int32_t*>(&triangle[index(sx, sy)]));
            n += uint64_t(std::popcount(simd::bits(andnot(ids == none, inside))));
        }
    return n;
}

void rasterize_opaque(const TriangleSetup& t, const TileRect& tile, TileBuffers& buffers) {
    float* depth = buffers.depth.data();
    uint32_t* ids = buffers.triangle.data();
    const vint id(int32_t(t.triangle));
    if (buffers.samples > 1) {
        const SampleLanes samples(t, sample_pattern(buffers.samples));
        const size_t plane = buffers.plane();
        traverse<true>(t, tile, buffers.size, &samples, [&](size_t index, int, int, int s, vmask covered, vfloat z) {
            const size_t i = size_t(s) * plane + index;
            const vmask pass = covered & (z < vfloat::load(depth + i));
            simd::store_masked(depth + i, pass, z);
            simd::store_masked(ids + i, pass, id);
        });
        return;
    }
    traverse<false>(t, tile, buffers.size, nullptr, [&](size_t index, int, int, vmask covered, vfloat z) {
        const vmask pass = covered & (z < vfloat::load(depth + index));
        simd::store_masked(depth + index, pass, z);
        simd::store_masked(ids + index, pass, id);
    });
}

void rasterize_depth(const TriangleSetup& t, const TileRect& tile, TileBuffers& buffers) {
    float* depth = buffers.depth.data();
    if (buffers.samples > 1) {
        const SampleLanes samples(t, sample_pattern(buffers.samples));
        const size_t plane = buffers.plane();
        traverse<true>(t, tile, buffers.size, &samples, [&](size_t index, int, int, int s, vmask covered, vfloat z) {
            float* d = depth + size_t(s) * plane + index;
            simd::store_masked(d, covered & (z < vfloat::load(d)), z);
        });
        return;
    }
    traverse<false>(t, tile, buffers.size, nullptr, [&](size_t index, int, int, vmask covered, vfloat z) {
        simd::store_masked(depth + index, covered & (z < vfloat::load(depth + index)), z);
    });
}

size_t rasterize_tested(const TriangleSetup& t, const TileRect& tile, const float* depth,
                        size_t stride, Fragment* out) {
    // Row-major depth, so lanes are tested one by one (transparency is the rare path).
    alignas(64) float z_lanes[kLanes];
    size_t n = 0;
    const int tile_size = 1 << 8;  // any stamp-aligned width works: indices are unused here
    traverse<false>(t, tile, tile_size, nullptr, [&](size_t, int sx, int sy, vmask covered, vfloat z) {
        (z + vfloat(1.0f)).store(z_lanes);  // window_depth(), as `depth` holds
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

size_t rasterize_tested_samples(const TriangleSetup& t, const Tile& tile, Fragment* out) {
    const int n = tile.sample_count;
    const SampleLanes samples(t, sample_pattern(n));
    const TileRect& rect = tile.rect;
    // Where sample s of a lane's pixel has its depth: the tile's sample depths, or its one
    // depth per pixel for every sample.
    const bool own = tile.sample_depth != nullptr;
    const float* depth = own ? tile.sample_depth : tile.depth;
    const vint row(int32_t(own ? tile.sample_depth_row : tile.stride));
    const vint pixel_step(int32_t(own ? tile.sample_depth_pixel_step : 1));
    const size_t sample_step = own ? tile.sample_depth_sample_step : 0;
    // A stamp's samples come one after another (traverse_sample_stamps): per lane, the
    // pixel's depth index and surface samples are read at the first, the passing samples and
    // their nearest depth gathered over all, and the fragments handed out after the last.
    vint index(0), surface(0), passed(0);
    vfloat nearest(0.0f);
    alignas(64) int32_t lanes[kLanes];
    alignas(64) float depths[kLanes];
    size_t count = 0;
    const int tile_size = 1 << 8;  // any stamp-aligned width works: indices are unused here
    traverse<true>(t, rect, tile_size, &samples, [&](size_t, int sx, int sy, int s, vmask covered, vfloat z) {
        if (s == 0) {
            const vint x = vint(sx) + simd::stamp_x(), y = vint(sy) + simd::stamp_y();
            const vmask inside = (x < vint(rect.x1)) & (y < vint(rect.y1)) & (x >= vint(rect.x0)) & (y >= vint(rect.y0));
            index = simd::select(inside, (y - vint(rect.y0)) * row + (x - vint(rect.x0)) * pixel_step, vint(0));
            for (int lane = 0; lane < kLanes; ++lane) {
                const int px = sx + lane % kStampW, py = sy + lane / kStampW;
                const bool in = px >= rect.x0 && py >= rect.y0 && px < rect.x1 && py < rect.y1;
                lanes[lane] = in ? int32_t(tile.sample_mask[tile.offset(px, py)]) : 0;
            }
            surface = vint::load(lanes);
            passed = vint(0);
            nearest = vfloat(2.0f);  // beyond any window depth
        }
        const vint bit(int32_t(1) << s);
        const vfloat z_window = z + vfloat(1.0f);  // window_depth(), as the sample depths hold
        const vmask pass = andnot((surface & bit) == vint(0), covered) &
                           (z_window < simd::gather(depth + size_t(s) * sample_step, index));
        passed = passed | simd::select(pass, bit, vint(0));
        nearest = simd::select(pass, simd::min(nearest, z_window), nearest);
        if (s != n - 1) return;
        const uint32_t any = simd::bits(andnot(passed == vint(0), vmask(true)));
        if (!any) return;
        passed.store(lanes);
        nearest.store(depths);
        for (uint32_t bits = any; bits; bits &= bits - 1) {
            const int lane = std::countr_zero(bits);
            out[count++] = {uint16_t(sx + lane % kStampW), uint16_t(sy + lane / kStampW), depths[lane],
                            uint16_t(lanes[lane])};
        }
    });
    return count;
}

size_t rasterize_tested_samples_reference(const TriangleSetup& t, const Tile& tile, Fragment* out) {
    const std::span<const SampleOffset> pattern = sample_pattern(tile.sample_count);
    const TileRect& rect = tile.rect;
    size_t count = 0;
    const int x0 = std::max<int>(t.minx, rect.x0), x1 = std::min<int>(t.maxx, rect.x1 - 1);
    const int y0 = std::max<int>(t.miny, rect.y0), y1 = std::min<int>(t.maxy, rect.y1 - 1);
    for (int y = y0; y <= y1; ++y)
        for (int x = x0; x <= x1; ++x) {
            Fragment f{uint16_t(x), uint16_t(y), 0.0f, 0};
            for (int s = 0; s < tile.sample_count; ++s) {
                if (!((tile.sample_mask[tile.offset(x, y)] >> s) & 1)) continue;
                bool inside = true;
                for (int i = 0; i < 3; ++i)
                    inside = inside && edge_at(t, i, x, y) + sample_offset(t, i, pattern[s].x, pattern[s].y) >= 0;
                if (!inside) continue;
                const float z = window_depth(depth_offset_at_sample(t, x, y, pattern[s].x, pattern[s].y));
                if (!(z < tile.depth_at_sample(x, y, s))) continue;
                f.depth = f.mask == 0 || z < f.depth ? z : f.depth;
                f.mask = uint16_t(f.mask | (1u << s));
            }
            if (f.mask) out[count++] = f;
        }
    return count;
}

}  // namespace tessera::pipeline
