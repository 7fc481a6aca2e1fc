#include "raster/shade/background_radiance.h"

#include <cmath>
#include <limits>

#include "raster/texture/sampler.h"

namespace tessera::shade {
namespace {

using simd::vfloat;
template <class F>
using V3 = simd::V3<F>;

// The weight of the zenith colour at elevation sine `up` >= 0: sqrt(up), whose slope is
// infinite at the horizon, eased in over the lowest kHorizonBand by smoothstep so that its
// slope is 0 there. A kink in the sky's gradient is a bright line at the horizon, and a curved
// mirror (the metaballs' reflections) shows it as a crease.
constexpr float kHorizonBand = 0.1f;  // sine of the elevation, about 5.7 degrees
constexpr float kGroundBand = 0.25f;  // below the horizon, down to the ground colour

// glm::mix of two constant colours: x (1 - a) + y a.
template <class F>
V3<F> mix(glm::vec3 x, glm::vec3 y, F a) {
    const F keep = F(1.0f) - a;
    return {F(x.x) * keep + F(y.x) * a, F(x.y) * keep + F(y.y) * a, F(x.z) * keep + F(y.z) * a};
}

// c^64 for c in [0, 1], the sun's glow: six squarings in double precision, rounded once to
// float. The double result is within 63 * 2^-53 (relative) of the exact power, so the float
// is the correctly rounded c^64 unless c^64 lies within 2^-47 of a rounding tie (std::pow's
// float is within one unit in the last place). Double lanes are IEEE in every instruction
// set, so the lanes give the one-direction value whatever the width; the compiler vectorises
// the loop (conversion, six multiplies, conversion per half register).
float power64(float c) {
    double x = c;
    for (int i = 0; i < 6; ++i) x *= x;
    return float(x);
}
vfloat power64(vfloat c) {
    alignas(64) float lanes[simd::kLanes];
    c.store(lanes);
    for (float& l : lanes) l = power64(l);
    return vfloat::load(lanes);
}

// The procedural sky (background.h) along unit directions d. Both sides of each choice are
// computed and selected, with finite values in the lanes not taken (sqrt of max(up, 0)).
template <class F>
V3<F> sky_radiance(const scene::Sky& sky, const V3<F>& d) {
    const F up = d.y;
    const F zenith_weight = simd::sqrt(simd::max(up, F(0.0f))) * simd::smoothstep(0.0f, kHorizonBand, up);
    const F ground_weight = simd::smoothstep(0.0f, kGroundBand, F(0.0f) - up);
    V3<F> c = simd::select(F(0.0f) <= up, mix(sky.horizon, sky.zenith, zenith_weight),
                           mix(sky.horizon, sky.ground, ground_weight));
    const float len = glm::length(sky.sun_direction);
    if (!(len > 0.0f)) return c;
    const glm::vec3 s = sky.sun_direction / len;
    const F cosine = (d.x * F(s.x) + d.y * F(s.y)) + d.z * F(s.z);  // glm::dot's order
    const auto glowing = F(0.0f) < cosine;
    if (simd::any_lane(glowing)) {
        const F glow = F(0.02f) * power64(simd::max(cosine, F(0.0f)));
        const V3<F> lit{c.x + F(sky.sun.x) * glow, c.y + F(sky.sun.y) * glow, c.z + F(sky.sun.z) * glow};
        c = simd::select(glowing, lit, c);
    }
    const V3<F> sun{F(sky.sun.x), F(sky.sun.y), F(sky.sun.z)};
    return simd::select(F(0.9995f) < cosine, sun, c);  // a disc of about 1.8 degrees
}

// The unit vector along d (glm::length, then a division per component), or (0, 0, -1) where
// d has zero, infinite or NaN length.
template <class F>
V3<F> unit_direction(const V3<F>& d) {
    const F len = simd::sqrt((d.x * d.x + d.y * d.y) + d.z * d.z);
    const auto ok = simd::both(F(0.0f) < len, len < F(std::numeric_limits<float>::infinity()));
    const F safe = simd::select(ok, len, F(1.0f));
    return simd::select(ok, V3<F>{d.x / safe, d.y / safe, d.z / safe}, V3<F>{F(0.0f), F(0.0f), F(-1.0f)});
}

glm::vec3 cube_radiance(const scene::CubeMap& cube, glm::vec3 d) {
    const glm::vec3 a = glm::abs(d);
    int face;
    float sc, tc, ma;
    if (a.x >= a.y && a.x >= a.z) {
        face = d.x >= 0.0f ? 0 : 1;
        sc = d.x >= 0.0f ? -d.z : d.z;
        tc = -d.y;
        ma = a.x;
    } else if (a.y >= a.z) {
        face = d.y >= 0.0f ? 2 : 3;
        sc = d.x;
        tc = d.y >= 0.0f ? d.z : -d.z;
        ma = a.y;
    } else {
        face = d.z >= 0.0f ? 4 : 5;
        sc = d.z >= 0.0f ? d.x : -d.x;
        tc = -d.y;
        ma = a.z;
    }
    const texture::Texture* texture = cube.faces[size_t(face)].get();
    if (!texture || !(ma > 0.0f)) return glm::vec3(0.0f);
    const float s = 0.5f * (sc / ma + 1.0f), t = 0.5f * (tc / ma + 1.0f);
    return glm::vec3(texture::sample(*texture, {s, 1.0f - t}, {}, texture::TextureFilter::bilinear, texture::TextureWrap::clamp));
}

}  // namespace

glm::vec3 background_radiance(const scene::Background& background, glm::vec3 direction) {
    const V3<float> d = unit_direction(V3<float>{direction.x, direction.y, direction.z});
    switch (background.kind) {
        case scene::Background::Kind::colour: return background.colour;
        case scene::Background::Kind::sky: {
            const V3<float> c = sky_radiance(background.sky, d);
            return {c.x, c.y, c.z};
        }
        case scene::Background::Kind::cube_map: return cube_radiance(background.cube, {d.x, d.y, d.z});
    }
    return background.colour;
}

V3<vfloat> background_radiance_lanes(const scene::Background& background, const V3<vfloat>& direction) {
    switch (background.kind) {
        case scene::Background::Kind::colour: break;
        case scene::Background::Kind::sky: return sky_radiance(background.sky, unit_direction(direction));
        case scene::Background::Kind::cube_map: {
            // Texture lookups one lane at a time (bilinear from one of six faces).
            alignas(64) float x[simd::kLanes], y[simd::kLanes], z[simd::kLanes];
            direction.x.store(x);
            direction.y.store(y);
            direction.z.store(z);
            for (int i = 0; i < simd::kLanes; ++i) {
                const glm::vec3 c = background_radiance(background, glm::vec3(x[i], y[i], z[i]));
                x[i] = c.x;
                y[i] = c.y;
                z[i] = c.z;
            }
            return {vfloat::load(x), vfloat::load(y), vfloat::load(z)};
        }
    }
    const glm::vec3 c = background.colour;
    return {vfloat(c.x), vfloat(c.y), vfloat(c.z)};
}

}  // namespace tessera::shade
