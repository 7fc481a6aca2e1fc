#include "raster/pipeline/vertex_stage.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cfloat>

namespace tessera::pipeline {

namespace {

using simd::vfloat;
using simd::vint;
using simd::vmask;

// Lanes where v is finite (NaN fails every ordered comparison, infinities exceed FLT_MAX).
vmask finite(vfloat v) { return simd::max(v, vfloat(0.0f) - v) <= vfloat(FLT_MAX); }

vint code_bit(vmask m, uint32_t bit) { return simd::select(m, vint(int32_t(bit)), vint(0)); }

}  // namespace

uint32_t clip_code(const Viewport& viewport, float x, float y, float z, float w) {
    const bool is_finite = std::isfinite(x) && std::isfinite(y) && std::isfinite(z) && std::isfinite(w);
    if (!is_finite) return kClipNear | kClipFar | kClipLeft | kClipRight | kClipTop | kClipBottom | kClipInvalid;
    const float gx = viewport.guard_x * w, gy = viewport.guard_y * w;
    uint32_t code = 0;
    // w below FLT_MIN overflows 1 / w in the projection: such a vertex goes to the clipper,
    // which drops what it cannot project (clip.cpp).
    if (!(-w <= z) || !(w >= FLT_MIN)) code |= kClipNear;
    if (!(z <= w)) code |= kClipFar;
    if (!(-gx <= x)) code |= kClipLeft;
    if (!(x <= gx)) code |= kClipRight;
    if (!(y <= gy)) code |= kClipTop;
    if (!(-gy <= y)) code |= kClipBottom;
    return code;
}

void run_vertex_stage(const Mesh& mesh, const glm::mat4& vp, const Viewport& viewport,
                      ClipVertices& out) {
    const size_t n = mesh.vertex_count();
    if (n == 0) {
        for (auto* v : {&out.x, &out.y, &out.z, &out.w}) v->clear();
        out.projected.clear();
        return;
    }
    // Padded to whole SIMD vectors so the last vector needs no special case.
    const size_t padded = (n + simd::kLanes - 1) / simd::kLanes * simd::kLanes;
    for (auto* v : {&out.x, &out.y, &out.z, &out.w}) v->resize(padded);
    out.projected.resize(padded);

    const float* positions = reinterpret_cast<const float*>(mesh.positions.data());
    static_assert(sizeof(glm::vec3) == 3 * sizeof(float));
    const size_t vectors = padded / simd::kLanes;
    tbb::parallel_for(tbb::blocked_range<size_t>(0, vectors, 256), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t v = r.begin(); v != r.end(); ++v) {
            const size_t base = v * simd::kLanes;
            // Lanes past the end re-read the last vertex (their results are never used).
            const vint last(int32_t(n - 1));
            vint index = vint(int32_t(base)) + simd::lane_index();
            index = simd::select(index < last, index, last);
            const vint offset = index * vint(3);
            const vfloat px = simd::gather(positions, offset);
            const vfloat py = simd::gather(positions + 1, offset);
            const vfloat pz = simd::gather(positions + 2, offset);
            vfloat cx, cy, cz, cw;
            clip_position(vp, px, py, pz, cx, cy, cz, cw);

            const vfloat gx = vfloat(viewport.guard_x) * cw, gy = vfloat(viewport.guard_y) * cw;
            const vmask all(true);
            const vmask ok = finite(cx) & finite(cy) & finite(cz) & finite(cw);
            vint code = code_bit(simd::andnot((vfloat(0.0f) - cw <= cz) & (vfloat(FLT_MIN) <= cw), all), kClipNear) |
                        code_bit(simd::andnot(cz <= cw, all), kClipFar) |
                        code_bit(simd::andnot(vfloat(0.0f) - gx <= cx, all), kClipLeft) |
                        code_bit(simd::andnot(cx <= gx, all), kClipRight) |
                        code_bit(simd::andnot(cy <= gy, all), kClipTop) |
                        code_bit(simd::andnot(vfloat(0.0f) - gy <= cy, all), kClipBottom);
            code = simd::select(ok, code, vint(int32_t(kClipNear | kClipFar | kClipLeft | kClipRight |
                                                       kClipTop | kClipBottom | kClipInvalid)));
            const vmask inside = code == vint(0);

            vfloat wx, wy, wz;
            viewport.to_window(cx, cy, cz, simd::select(inside, cw, vfloat(1.0f)), wx, wy, wz);
            const vfloat sub = vfloat(float(kSubpixels));
            const vint X = simd::round_to_int(simd::select(inside, wx * sub, vfloat(0.0f)));
            const vint Y = simd::round_to_int(simd::select(inside, wy * sub, vfloat(0.0f)));

            cx.store(&out.x[base]);
            cy.store(&out.y[base]);
            cz.store(&out.z[base]);
            cw.store(&out.w[base]);
            // Interleave into the 16-byte records.
            alignas(64) int32_t xs[simd::kLanes], ys[simd::kLanes], codes[simd::kLanes];
            alignas(64) float zs[simd::kLanes];
            X.store(xs);
            Y.store(ys);
            wz.store(zs);
            code.store(codes);
            for (int i = 0; i < simd::kLanes; ++i)
                out.projected[base + i] = {{xs[i], ys[i], zs[i]}, uint32_t(codes[i])};
        }
    });
    for (auto* v : {&out.x, &out.y, &out.z, &out.w}) v->resize(n);
    out.projected.resize(n);
}

}  // namespace tessera::pipeline
