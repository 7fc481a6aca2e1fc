// The per-pixel shading kernel, written once over the lane type F: float (one pixel, the
// scalar reference) or simd::vfloat (kLanes pixels of one material). Internal to
// frame_shading.cpp; see frame_shading.h for the formulas.
#pragma once
#include <glm/glm.hpp>

#include <span>

#include "raster/scene/light.h"
#include "raster/scene/material.h"
#include "raster/shade/lighting.h"
#include "raster/simd/lane_math.h"
#include "raster/shade/tangent_frame.h"
#include "raster/texture/sampler.h"
#include "raster/texture/sampler_simd.h"

namespace tessera::shade {

// Written once in the lane arithmetic of simd/lane_math.h, for float and simd::vfloat.
using namespace simd;

inline constexpr int kLanes = simd::kLanes;

// The inputs of up to kLanes pixels that share one material, gathered per corner k of each
// pixel's triangle, structure-of-arrays so that a vfloat load takes all lanes at once.
struct alignas(64) Lanes {
    float x[kLanes], y[kLanes];       // pixel centre in window coordinates (column + 0.5, row + 0.5)
    float bary[3][3][kLanes];         // PerspectiveBarycentrics::e of the pixel's triangle
    float pos[3][3][kLanes];          // corner, world position
    float nrm[3][3][kLanes];          // corner, world normal (zero when the mesh has none)
    float uv[3][2][kLanes];           // corner, texture coordinates
    float col[3][3][kLanes];          // corner, Gouraud colour
    // The side the tile rasterizer drew the triangle from, where it decides the lit side
    // (FrameShading::drawn_side()): +1 counter-clockwise in NDC, -1 clockwise, 0 undecided.
    float drawn[kLanes];
    float out[4][kLanes];             // result: linear RGBA
};

// What the kernel reads besides the lanes: uniform over the batch.
struct KernelContext {
    const scene::Material* material = nullptr;
    const texture::Texture* diffuse = nullptr;  // null: kd alone
    const texture::Texture* normal = nullptr;   // null: the interpolated normal
    std::span<const scene::Light> lights;
    glm::vec3 eye{0.0f};
};

template <class F>
constexpr int lane_width() {
    if constexpr (std::is_same_v<F, float>) return 1;
    else return kLanes;
}
template <class F>
F lane_load(const float* a, int lane) {
    if constexpr (std::is_same_v<F, float>) return a[lane];
    else return F::load(a);
}
template <class F>
void lane_store(float* a, int lane, F v) {
    if constexpr (std::is_same_v<F, float>) a[lane] = v;
    else v.store(a);
}

template <class F>
struct Texel {
    F r, g, b, a;
};

// The reference path samples one pixel with sample(); the SIMD path gathers all lanes at once.
template <class F>
Texel<F> sample_texture(const texture::Texture& texture, const scene::Material& m, F u, F v, F du_dx, F dv_dx, F du_dy, F dv_dy) {
    if constexpr (std::is_same_v<F, float>) {
        const glm::vec4 t = texture::sample(texture, {u, v}, {{du_dx, dv_dx}, {du_dy, dv_dy}}, m.filter, m.wrap);
        return {t.r, t.g, t.b, t.a};
    } else {
        const texture::TexelLanes t = texture::sample_lanes(texture, u, v, du_dx, dv_dx, du_dy, dv_dy, m.filter, m.wrap);
        return {t.r, t.g, t.b, t.a};
    }
}

template <class F>
void shade_lanes(const KernelContext& ctx, Lanes& d, int lane) {
    using V = V3<F>;
    const scene::Material& m = *ctx.material;
    const auto ld = [&](const float* a) { return lane_load<F>(a, lane); };
    const auto v3 = [&](const float (&a)[3][kLanes]) { return V{ld(a[0]), ld(a[1]), ld(a[2])}; };
    const F zero(0.0f), one(1.0f);

    V p[3], n[3], e[3];
    for (int k = 0; k < 3; ++k) {
        e[k] = v3(d.bary[k]);
        p[k] = v3(d.pos[k]);
        n[k] = v3(d.nrm[k]);
    }
    // Perspective-correct barycentrics (barycentrics.h): r_i = e_i . (x, y, 1), b = r / sum(r).
    const V q{ld(d.x), ld(d.y), one};
    const F lambda[3] = {dot(e[0], q), dot(e[1], q), dot(e[2], q)};
    const F sum = lambda[0] + lambda[1] + lambda[2];
    const F inv_sum = one / select(abs_of(sum) < F(1e-30f), one, sum);
    const F b[3] = {lambda[0] * inv_sum, lambda[1] * inv_sum, lambda[2] * inv_sum};

    const V position = madd(p[0], b[0], madd(p[1], b[1], p[2] * b[2]));
    const V eye = broadcast<F>(ctx.eye);
    // The face normal, oriented like the vertex normals when the mesh has them (so meshes of
    // either winding convention light correctly), else by the counter-clockwise winding.
    V face = normalize_or(cross(p[1] - p[0], p[2] - p[0]), V{zero, zero, one});
    const V corner_normals = n[0] + n[1] + n[2];
    const F winding = select(dot(face, corner_normals) < zero, F(-1.0f), one);
    face = face * winding;
    // Two-sided lighting: a surface seen from behind is lit as its back side (the flag). Where
    // the rasterizer says which side it drew (a sliver whose side its snapped vertices
    // decide), that side is lit.
    const auto back = dot(face, eye - p[0]) < zero;
    const F drawn = ld(d.drawn);
    const F side = select((drawn < zero) | (zero < drawn), drawn * winding, select(back, F(-1.0f), one));
    V normal = normalize_or(madd(n[0], b[0], madd(n[1], b[1], n[2] * b[2])), face) * side;
    face = face * side;
    const V view = normalize_or(eye - position, face);

    V kd = broadcast<F>(m.kd);
    V ka = broadcast<F>(m.ka);
    F alpha(m.opacity);
    if (ctx.diffuse || ctx.normal) {
        // uv and its derivatives per pixel step, analytic from the same plane equations:
        // d b_i / dx = (e_i.x - b_i sum(e.x)) / sum(r), and likewise for y.
        const F ax = e[0].x + e[1].x + e[2].x, ay = e[0].y + e[1].y + e[2].y;
        F u = zero, v = zero, udx = zero, vdx = zero, udy = zero, vdy = zero;
        for (int k = 0; k < 3; ++k) {
            const F uk = ld(d.uv[k][0]) * F(m.uv_scale.x), vk = ld(d.uv[k][1]) * F(m.uv_scale.y);
            const F dbx = (e[k].x - b[k] * ax) * inv_sum;
            const F dby = (e[k].y - b[k] * ay) * inv_sum;
            u = fma(uk, b[k], u);
            v = fma(vk, b[k], v);
            udx = fma(uk, dbx, udx);
            vdx = fma(vk, dbx, vdx);
            udy = fma(uk, dby, udy);
            vdy = fma(vk, dby, vdy);
        }
        if (ctx.diffuse) {
            const Texel<F> t = sample_texture<F>(*ctx.diffuse, m, u, v, udx, vdx, udy, vdy);
            kd = kd * V{t.r, t.g, t.b};
            if (m.textured_ambient) ka = ka * V{t.r, t.g, t.b};
            alpha = alpha * t.a;
        }
        if (ctx.normal) {
            // The map stores tangent-space normals as RGB = n * 0.5 + 0.5.
            const Texel<F> t = sample_texture<F>(*ctx.normal, m, u, v, udx, vdx, udy, vdy);
            const V mapped{fma(t.r, F(2.0f), F(-1.0f)), fma(t.g, F(2.0f), F(-1.0f)), fma(t.b, F(2.0f), F(-1.0f))};
            const F s[3] = {ld(d.uv[0][0]), ld(d.uv[1][0]), ld(d.uv[2][0])};
            const F t3[3] = {ld(d.uv[0][1]), ld(d.uv[1][1]), ld(d.uv[2][1])};
            const TangentFrame<F> frame = tangent_frame<F>(p, s, t3, normal);
            // Back faces see the map from behind: its tangent axes flip with the normal.
            const V perturbed = madd(frame.s, mapped.x * side, madd(frame.t, mapped.y * side, normal * mapped.z));
            normal = normalize_or(perturbed, normal);
        }
    }

    V colour;
    switch (m.model) {
        case scene::ShadingModel::flat: {
            const V centroid = (p[0] + p[1] + p[2]) * F(1.0f / 3.0f);
            colour = blinn_phong<F>(ctx.lights, centroid, face, normalize_or(eye - centroid, face),
                                    ka, kd, broadcast<F>(m.ks), F(m.shine));
            break;
        }
        case scene::ShadingModel::gouraud: {
            const V g[3] = {v3(d.col[0]), v3(d.col[1]), v3(d.col[2])};
            colour = madd(g[0], b[0], madd(g[1], b[1], g[2] * b[2]));
            break;
        }
        case scene::ShadingModel::phong:
            colour = blinn_phong<F>(ctx.lights, position, normal, view, ka, kd,
                                    broadcast<F>(m.ks), F(m.shine));
            break;
        case scene::ShadingModel::toon: colour = toon<F>(ctx.lights, position, normal, view, kd); break;
    }
    // Alpha testing: the surface is there (1) or not (0), the cutoff compared in the same
    // lanes by both instantiations.
    if (m.masked()) alpha = select(alpha < F(m.alpha_cutoff), zero, one);
    lane_store(d.out[0], lane, colour.x);
    lane_store(d.out[1], lane, colour.y);
    lane_store(d.out[2], lane, colour.z);
    lane_store(d.out[3], lane, alpha);
}

}  // namespace tessera::shade
