#include "raster/pipeline/triangle_setup_lanes.h"

#include <bit>
#include <cstddef>

#include "raster/simd/lane_math.h"

namespace tessera::pipeline {

using simd::kLanes;
using simd::vint;
using simd::vmask;

vmask gather_corners(const uint32_t* corners, vint offset, vmask active, size_t readable,
                     const ProjectedVertex* records, size_t vertex_count, WindowLanes& out, vint& codes) {
    const int32_t* indices = reinterpret_cast<const int32_t*>(corners);
    vint index[3];
    if (readable >= size_t(kLanes) && simd::bits(active & (offset == simd::lane_index())) == simd::bits(active)) {
        simd::load_interleaved3(indices, index[0], index[1], index[2]);
    } else {
        const vint first = simd::select(active, offset * vint(3), vint(0));
        for (int k = 0; k < 3; ++k) index[k] = simd::gather_int(indices + k, first);
    }
    vmask valid = active;
    for (int k = 0; k < 3; ++k) {
        // Indices of 2^31 and more read as negative: below the count means valid.
        valid = valid & (vint(-1) < index[k]) & (index[k] < vint(int32_t(vertex_count)));
    }
    static_assert(sizeof(ProjectedVertex) == 4 * sizeof(int32_t) && offsetof(ProjectedVertex, code) == 12);
    const int32_t* words = reinterpret_cast<const int32_t*>(records);
    codes = vint(0);
    for (int k = 0; k < 3; ++k) {
        const vint record = simd::shift_left<2>(simd::select(valid, index[k], vint(0)));
        out.X[k] = simd::gather_int(words, record);
        out.Y[k] = simd::gather_int(words + 1, record);
        out.z[k] = simd::gather(reinterpret_cast<const float*>(words + 2), record);
        codes = codes | simd::gather_int(words + 3, record);
    }
    return valid;
}

void SmallSetups::write(int lane, TriangleSetup& t) const {
    for (int i = 0; i < 3; ++i) {
        t.f[i] = f[i][lane];
        t.dx[i] = dx[i][lane];
        t.dy[i] = dy[i][lane];
        t.residue[i] = uint8_t(residue[i][lane]);
    }
    t.depth.a = plane[0][lane];
    t.depth.b = plane[1][lane];
    t.depth.c = plane[2][lane];
    t.depth.ax = int16_t(anchor[0][lane]);
    t.depth.ay = int16_t(anchor[1][lane]);
    t.minx = int16_t(box[0][lane]);
    t.miny = int16_t(box[1][lane]);
    t.maxx = int16_t(box[2][lane]);
    t.maxy = int16_t(box[3][lane]);
    t.small = 1;
    t.transparent = 0;
    // holds_centres(): holds_sample() at the pixel centre makes setup_triangle's test (a
    // top-left edge whose constant part is a multiple of 256 that Bezout lets it meet); the
    // lanes did the first two tests (may_hold_centres), so the call is made only for the
    // rare edges that pass them.
    unsigned on_edge = 0;
    for (unsigned maybe = unsigned(may_hold_centres[lane]); maybe; maybe &= maybe - 1) {
        const int i = std::countr_zero(maybe);
        on_edge |= unsigned(holds_sample(t, i, 0, 0)) << i;
    }
    t.on_edge = uint8_t(on_edge);
}

namespace {

// setup_small_triangles; with kClassify, only as far as classify_small_triangles goes.
template <bool kClassify>
vmask small_triangles(const WindowLanes& v, vmask active, CullMode cull, const Viewport& viewport, int samples,
                      SmallSetups& out) {
    const vint xmin = simd::min(v.X[0], simd::min(v.X[1], v.X[2])), xmax = simd::max(v.X[0], simd::max(v.X[1], v.X[2]));
    const vint ymin = simd::min(v.Y[0], simd::min(v.Y[1], v.Y[2])), ymax = simd::max(v.Y[0], simd::max(v.Y[1], v.Y[2]));
    // Window coordinates lie within 2^22 (fixed_point.h): the extents do not wrap.
    const vint extent(kSmallExtent);
    const vmask lanes = active & (xmax - xmin < extent) & (ymax - ymin < extent);
    if (!simd::any(lanes)) {
        out.result_bits[0] = out.result_bits[1] = out.result_bits[2] = out.result_bits[3] = 0;
        return active;
    }

    // Twice the signed area (setup_triangle), exact in int32 here.
    const vint area2 = (v.X[1] - v.X[0]) * (v.Y[2] - v.Y[0]) - (v.Y[1] - v.Y[0]) * (v.X[2] - v.X[0]);
    const vint zero(0);
    const vmask front = area2 < zero;  // window y runs down: counter-clockwise in NDC
    const vmask flat = area2 == zero;
    const vmask culled = cull == CullMode::back ? andnot(front, vmask(true)) : cull == CullMode::front ? front : vmask(false);
    // Inside where every edge function is positive: swap corners 1 and 2 of front faces.
    const vint X[3] = {v.X[0], simd::select(front, v.X[2], v.X[1]), simd::select(front, v.X[1], v.X[2])};
    const vint Y[3] = {v.Y[0], simd::select(front, v.Y[2], v.Y[1]), simd::select(front, v.Y[1], v.Y[2])};

    // The pixel box (setup_triangle's lo / hi: pixel centres, or any sample, within the box).
    const int32_t lo = samples > 1 ? 0 : kSubpixels / 2 - 1, hi = samples > 1 ? 0 : kSubpixels / 2;
    const vint bits(kSubpixelBits);
    const vint minx = simd::max((xmin + vint(lo)) >> bits, zero);
    const vint maxx = simd::min((xmax - vint(hi)) >> bits, vint(viewport.width - 1));
    const vint miny = simd::max((ymin + vint(lo)) >> bits, zero);
    const vint maxy = simd::min((ymax - vint(hi)) >> bits, vint(viewport.height - 1));
    const vmask empty = (maxx < minx) | (maxy < miny);
    minx.store(out.box[0]), miny.store(out.box[1]), maxx.store(out.box[2]), maxy.store(out.box[3]);
    const uint32_t set_up = simd::bits(lanes), zero_area = simd::bits(flat);
    const uint32_t culled_face = simd::bits(culled), no_samples = simd::bits(empty);
    out.result_bits[0] = set_up & zero_area;
    out.result_bits[1] = set_up & ~zero_area & culled_face;
    out.result_bits[2] = set_up & ~zero_area & ~culled_face & no_samples;
    out.result_bits[3] = set_up & ~(zero_area | culled_face | no_samples);
    for (int lane = 0; lane < kLanes; ++lane) {
        const uint32_t bit = 1u << lane;
        if (!(set_up & bit)) continue;
        out.result[lane] = zero_area & bit     ? SetupResult::zero_area
                           : culled_face & bit ? SetupResult::culled_face
                           : no_samples & bit  ? SetupResult::no_samples
                                               : SetupResult::drawn;
    }
    if constexpr (kClassify) return andnot(lanes, active);

    // E at the first pixel centre P of the box, less one off top-left edges, as F and residue.
    const vint half(kSubpixels / 2);
    const vint px = simd::shift_left<kSubpixelBits>(minx) + half, py = simd::shift_left<kSubpixelBits>(miny) + half;
    vint may_hold(0);
    for (int i = 0; i < 3; ++i) {
        const int j = i == 2 ? 0 : i + 1;
        const vint dX = X[j] - X[i], dY = Y[j] - Y[i];
        const vmask top_left = (dY < zero) | ((dY == zero) & (zero < dX));
        const vint e = dX * (py - Y[i]) - dY * (px - X[i]) - simd::select(top_left, zero, vint(1));
        const vint residue = e & vint(kSubpixels - 1);
        (e >> bits).store(out.f[i]);
        residue.store(out.residue[i]);
        dX.store(out.dx[i]);
        dY.store(out.dy[i]);
        // holds_sample(t, i, 0, 0)'s first tests: top-left, residue (its sample step) 0.
        may_hold = may_hold | simd::select(top_left & (residue == zero), vint(1 << i), zero);
    }
    may_hold.store(out.may_hold_centres);

    // The depth planes (DepthPlane::from), for every lane: those of lanes that are not drawn
    // are never read.
    alignas(64) int32_t corner_x[3][kLanes], corner_y[3][kLanes];
    alignas(64) float corner_z[3][kLanes];
    for (int k = 0; k < 3; ++k) X[k].store(corner_x[k]), Y[k].store(corner_y[k]);
    v.z[0].store(corner_z[0]);
    simd::select(front, v.z[2], v.z[1]).store(corner_z[1]);
    simd::select(front, v.z[1], v.z[2]).store(corner_z[2]);
    for (int lane = 0; lane < kLanes; ++lane) {
        const int32_t x0 = corner_x[0][lane], y0 = corner_y[0][lane];
        const int32_t ax = x0 >> kSubpixelBits, ay = y0 >> kSubpixelBits;
        const double cx = (double(ax) + 0.5) - double(x0) / kSubpixels;
        const double cy = (double(ay) + 0.5) - double(y0) / kSubpixels;
        depth_plane_coefficients(corner_x[1][lane] - x0, corner_y[1][lane] - y0, corner_x[2][lane] - x0,
                                 corner_y[2][lane] - y0, corner_z[0][lane], corner_z[1][lane], corner_z[2][lane], cx,
                                 cy, out.plane[0][lane], out.plane[1][lane], out.plane[2][lane]);
        out.anchor[0][lane] = ax;
        out.anchor[1][lane] = ay;
    }
    return andnot(lanes, active);
}

}  // namespace

vmask classify_small_triangles(const WindowLanes& v, vmask active, CullMode cull, const Viewport& viewport,
                               int samples, SmallSetups& out) {
    return small_triangles<true>(v, active, cull, viewport, samples, out);
}

vmask setup_small_triangles(const WindowLanes& v, vmask active, CullMode cull, const Viewport& viewport,
                            int samples, SmallSetups& out) {
    return small_triangles<false>(v, active, cull, viewport, samples, out);
}

}  // namespace tessera::pipeline
