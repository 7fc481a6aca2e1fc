// The tangent frame of a triangle from its positions and texture coordinates (Lengyel's
// per-triangle tangent basis):
//     Vec1 = p3 - p2, Vec2 = p1 - p2, dS1 = s3 - s2, dS2 = s1 - s2,
//     tgT = |dS2 * Vec1 - dS1 * Vec2|,   tgS = |tgT x N|,
// computed per triangle and never averaged across triangles, so texture seams (where the
// same position carries two (s, t)) cannot produce a meaningless frame.
//
// Two additions the textbook formula leaves to the triangle order, made explicit here:
// - dS2 * Vec1 - dS1 * Vec2 is the in-plane direction along which s stays constant; t changes
//   along it by det = dS2 dT1 - dS1 dT2, so it is multiplied by det to point towards +t for
//   either uv winding;
// - tgS = tgT x N points towards +s only when the uv layout is not mirrored; where it points
//   against +s (the direction dT2 * Vec1 - dT1 * Vec2, scaled by -det) it is negated.
// tgT is made perpendicular to N first (N is the interpolated normal, not the flat triangle's),
// so (tgS, tgT, N) is orthonormal. A triangle with degenerate uv (det = 0) gets an arbitrary
// frame around N instead of NaN.
#pragma once
#include "raster/simd/lane_math.h"

namespace tessera::shade {

// Written once in the lane arithmetic of simd/lane_math.h, for float and simd::vfloat.
using namespace simd;

template <class F>
struct TangentFrame {
    V3<F> s;  // towards +s (texture u)
    V3<F> t;  // towards +t (texture v)
};

// Corner k has position p[k] and texture coordinates (s[k], t[k]); n is the unit normal.
template <class F>
TangentFrame<F> tangent_frame(const V3<F> p[3], const F s[3], const F t[3], V3<F> n) {
    const V3<F> vec1 = p[2] - p[1], vec2 = p[0] - p[1];
    const F ds1 = s[2] - s[1], ds2 = s[0] - s[1];
    const F dt1 = t[2] - t[1], dt2 = t[0] - t[1];
    const F det = ds2 * dt1 - ds1 * dt2;
    const V3<F> along_t = (vec1 * ds2 - vec2 * ds1) * det;
    const V3<F> along_s = (vec1 * dt2 - vec2 * dt1) * (F(0.0f) - det);
    // Any unit vector perpendicular to n: the fallback for degenerate uv.
    const V3<F> other = select(abs_of(n.x) < F(0.9f), V3<F>{F(1.0f), F(0.0f), F(0.0f)},
                               V3<F>{F(0.0f), F(1.0f), F(0.0f)});
    const V3<F> any_t = normalize_or(cross(n, other), V3<F>{F(0.0f), F(1.0f), F(0.0f)});
    const V3<F> tg_t = normalize_or(along_t - n * dot(n, along_t), any_t);
    const V3<F> tg_s = normalize_or(cross(tg_t, n), V3<F>{F(1.0f), F(0.0f), F(0.0f)});
    const auto mirrored = dot(tg_s, along_s) < F(0.0f);
    return {select(mirrored, tg_s * F(-1.0f), tg_s), tg_t};
}

}  // namespace tessera::shade
