// The texture sampler of sampler.h for kLanes pixels at once (simd::vfloat): the same filters,
// wrap modes and level selection, with the texel fetches as hardware gathers from the
// texture's packed mip chain (texture.h). Each lane may read a different mip level. The
// scalar sample() is its reference (tests compare them); lambda's log2 is the polynomial of
// simd/lane_math.h (log2_positive), within 2e-6 of std::log2.
#pragma once
#include "raster/simd/lane_math.h"
#include "raster/texture/sampler.h"
#include "raster/texture/texture.h"

namespace tessera::texture {

// Written in the lane arithmetic of simd/lane_math.h.
using namespace simd;

struct TexelLanes {
    vfloat r, g, b, a;
};

namespace sampler_detail {

inline vint clamp_index(vint i, vint size) {
    i = select(i < vint(0), vint(0), i);
    return select(i < size, i, size - vint(1));
}

// As sampler.cpp: repeat coordinates arrive reduced to [0, 1), so one step wraps an index.
inline vint wrap_index(vint i, vint size, TextureWrap wrap) {
    if (wrap == TextureWrap::repeat) {
        i = select(i < vint(0), i + size, i);
        i = select(i >= size, i - size, i);
    }
    return clamp_index(i, size);
}

inline vfloat safe_coordinate(vfloat t, TextureWrap wrap) {
    t = select(abs_of(t) < vfloat(3.0e38f), t, vfloat(0.0f));  // NaN and infinities -> 0
    if (wrap == TextureWrap::repeat) return t - floor_of(t);
    return min(max(t, vfloat(-1.0f)), vfloat(2.0f));
}

inline vfloat mix(vfloat a, vfloat b, vfloat t) { return a * (vfloat(1.0f) - t) + b * t; }
inline TexelLanes mix(const TexelLanes& a, const TexelLanes& b, vfloat t) {
    return {mix(a.r, b.r, t), mix(a.g, b.g, t), mix(a.b, b.b, t), mix(a.a, b.a, t)};
}

inline TexelLanes fetch(const Texture& texture, vint texel) {
    TexelLanes t;
    simd::gather_quads(&texture.texels()->r, texel, t.r, t.g, t.b, t.a);
    return t;
}

inline TexelLanes nearest(const Texture& texture, vfloat u, vfloat v, TextureWrap wrap) {
    const vint w(texture.widths()[0]), h(texture.heights()[0]);
    const vint x = wrap_index(simd::round_to_int(floor_of(u * simd::to_float(w))), w, wrap);
    const vint y = wrap_index(simd::round_to_int(floor_of(v * simd::to_float(h))), h, wrap);
    return fetch(texture, y * w + x);
}

inline TexelLanes bilinear(const Texture& texture, vint level, vfloat u, vfloat v, TextureWrap wrap) {
    const vint w = gather_int(texture.widths(), level), h = gather_int(texture.heights(), level);
    const vint offset = gather_int(texture.offsets(), level);
    const vfloat fx = u * simd::to_float(w) - vfloat(0.5f), fy = v * simd::to_float(h) - vfloat(0.5f);
    const vfloat x0f = floor_of(fx), y0f = floor_of(fy);
    const vfloat ax = fx - x0f, ay = fy - y0f;
    const vint x0i = simd::round_to_int(x0f), y0i = simd::round_to_int(y0f);
    const vint x0 = wrap_index(x0i, w, wrap), x1 = wrap_index(x0i + vint(1), w, wrap);
    const vint row0 = offset + wrap_index(y0i, h, wrap) * w, row1 = offset + wrap_index(y0i + vint(1), h, wrap) * w;
    const TexelLanes bottom = mix(fetch(texture, row0 + x0), fetch(texture, row0 + x1), ax);
    const TexelLanes top = mix(fetch(texture, row1 + x0), fetch(texture, row1 + x1), ax);
    return mix(bottom, top, ay);
}

}  // namespace sampler_detail

// Filtered texels at (u, v) with the uv derivatives per pixel step (sampler.h).
inline TexelLanes sample_lanes(const Texture& texture, vfloat u, vfloat v, vfloat du_dx, vfloat dv_dx,
                               vfloat du_dy, vfloat dv_dy, TextureFilter filter, TextureWrap wrap) {
    using namespace sampler_detail;
    u = safe_coordinate(u, wrap);
    v = safe_coordinate(v, wrap);
    if (filter == TextureFilter::nearest) return nearest(texture, u, v, wrap);
    if (filter == TextureFilter::bilinear) return bilinear(texture, vint(0), u, v, wrap);

    const vfloat w(float(texture.width())), h(float(texture.height()));
    const vfloat x_step = du_dx * w, y_step = dv_dx * h, x_step2 = du_dy * w, y_step2 = dv_dy * h;
    const vfloat along_x = sqrt(x_step * x_step + y_step * y_step), along_y = sqrt(x_step2 * x_step2 + y_step2 * y_step2);
    // A NaN derivative counts as no footprint along its axis (as mip_lambda).
    const vfloat rho = max(select(along_x <= vfloat(INFINITY), along_x, vfloat(0.0f)),
                           select(along_y <= vfloat(INFINITY), along_y, vfloat(0.0f)));
    const vfloat safe_rho = max(rho, vfloat(1e-30f));  // log2 of a zero footprint: level 0 anyway
    const vfloat top(float(texture.level_count() - 1));
    const vfloat lambda = min(max(log2_positive(safe_rho), vfloat(0.0f)), top);
    if (filter == TextureFilter::mipmap)
        return bilinear(texture, simd::round_to_int(floor_of(lambda + vfloat(0.5f))), u, v, wrap);
    const vfloat lower = floor_of(lambda);
    const vfloat upper = min(lower + vfloat(1.0f), top);
    return mix(bilinear(texture, simd::round_to_int(lower), u, v, wrap),
               bilinear(texture, simd::round_to_int(upper), u, v, wrap), lambda - lower);
}

}  // namespace tessera::texture
