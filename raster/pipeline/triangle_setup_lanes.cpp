#include "raster/pipeline/triangle_setup_lanes.h"

namespace tessera::pipeline {

using simd::kLanes;
using simd::vint;
using simd::vmask;

void SmallSetups::write(int lane, TriangleSetup& t) const {
    for (int i = 0; i < 3; ++i) {
        t.f[i] = f[i][lane];
        t.dx[i] = dx[i][lane];
        t.dy[i] = dy[i][lane];
        t.residue[i] = uint8_t(residue[i][lane]);
    }
    t.depth = DepthPlane::from({X[0][lane], Y[0][lane], z[0][lane]}, {X[1][lane], Y[1][lane], z[1][lane]},
                               {X[2][lane], Y[2][lane], z[2][lane]});
    t.minx = int16_t(box[0][lane]);
    t.miny = int16_t(box[1][lane]);
    t.maxx = int16_t(box[2][lane]);
    t.maxy = int16_t(box[3][lane]);
    t.small = 1;
    t.transparent = 0;
}

vmask setup_small_triangles(const WindowLanes& v, vmask active, CullMode cull, const Viewport& viewport,
                            int samples, SmallSetups& out) {
    const vint xmin = simd::min(v.X[0], simd::min(v.X[1], v.X[2])), xmax = simd::max(v.X[0], simd::max(v.X[1], v.X[2]));
    const vint ymin = simd::min(v.Y[0], simd::min(v.Y[1], v.Y[2])), ymax = simd::max(v.Y[0], simd::max(v.Y[1], v.Y[2]));
    // Window coordinates lie within 2^22 (fixed_point.h): the extents do not wrap.
    const vint extent(kSmallExtent);
    const vmask lanes = active & (xmax - xmin < extent) & (ymax - ymin < extent);
    if (!simd::any(lanes)) return active;

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

    // E at the first pixel centre P of the box, less one off top-left edges, as F and residue.
    const vint half(kSubpixels / 2);
    const vint px = simd::shift_left<kSubpixelBits>(minx) + half, py = simd::shift_left<kSubpixelBits>(miny) + half;
    for (int i = 0; i < 3; ++i) {
        const int j = i == 2 ? 0 : i + 1;
        const vint dX = X[j] - X[i], dY = Y[j] - Y[i];
        const vmask top_left = (dY < zero) | ((dY == zero) & (zero < dX));
        const vint e = dX * (py - Y[i]) - dY * (px - X[i]) - simd::select(top_left, zero, vint(1));
        (e >> bits).store(out.f[i]);
        (e & vint(kSubpixels - 1)).store(out.residue[i]);
        dX.store(out.dx[i]);
        dY.store(out.dy[i]);
    }
    minx.store(out.box[0]), miny.store(out.box[1]), maxx.store(out.box[2]), maxy.store(out.box[3]);
    for (int k = 0; k < 3; ++k) X[k].store(out.X[k]), Y[k].store(out.Y[k]);
    v.z[0].store(out.z[0]);
    simd::select(front, v.z[2], v.z[1]).store(out.z[1]);
    simd::select(front, v.z[1], v.z[2]).store(out.z[2]);

    const uint32_t set_up = simd::bits(lanes), zero_area = simd::bits(flat);
    const uint32_t culled_face = simd::bits(culled), no_samples = simd::bits(empty);
    for (int lane = 0; lane < kLanes; ++lane) {
        const uint32_t bit = 1u << lane;
        if (!(set_up & bit)) continue;
        out.result[lane] = zero_area & bit     ? SetupResult::zero_area
                           : culled_face & bit ? SetupResult::culled_face
                           : no_samples & bit  ? SetupResult::no_samples
                                               : SetupResult::drawn;
    }
    return andnot(lanes, active);
}

}  // namespace tessera::pipeline
