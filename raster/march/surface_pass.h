// The ray-marched surface as a per-pixel compute pass in the tile stage (the GPU original
// draws the marched terrain as a full-screen pass; here it runs per tile after rasterization).
//
// For each run of kMarchLanes pixels in a tile row: generate the rays, let the surface bound
// them, cut each lane's interval at whatever is already in the depth buffer (a rasterized
// triangle, or an earlier marched surface) and at the far plane, march the packet, and where
// the hit's window depth (through the same view-projection as the rasterizer) is strictly
// nearer than the stored depth, write depth and the shaded colour. So marched surfaces and
// triangles occlude each other exactly as two triangles would, and the march never spends a
// step behind a rasterized surface.
//
// A tile reads and writes only its own pixels and each pixel's result depends only on its
// ray, so tiles can run in parallel in any order with identical output.
#pragma once
#include <algorithm>
#include <bit>
#include <cstdint>
#include <vector>

#include "raster/march/march.h"
#include "raster/march/march_settings.h"
#include "raster/core/tile.h"
#include "raster/march/ray_generation.h"
#include "raster/march/surface_normal.h"
#include "raster/march/surface_shading.h"
#include "raster/shade/background_radiance.h"
#include "raster/core/visibility.h"
#include "raster/simd/lane_math.h"

namespace tessera::march {

struct SurfaceLook {
    SurfaceMaterial material{};
    // A sun above and behind the viewer's right shoulder for views towards -z.
    std::vector<scene::Light> lights{scene::directional_light({0.5f, 0.8f, 0.6f}, glm::vec3(0.12f), glm::vec3(1.0f))};
    NormalSettings normals{};
};

template <class Surface>
class SurfacePass {
public:
    // Validates the settings (std::invalid_argument). The generator and background are
    // borrowed and must outlive the pass.
    SurfacePass(Surface surface, const RayGenerator& rays, const MarchSettings& settings,
                const SurfaceLook& look, const scene::Background& background)
        : surface_(surface), rays_(rays), settings_(settings), look_(look), background_(background) {
        surface_.validate();
        settings_.validate();
        look_.normals.validate();
    }

    // A packet's march bounds, hits, depth test, normals and shading in lanes, after the
    // surface culls what the tile's rays may meet (when it can: Surface::bind_tile).
    void run(const Tile& target) const {
        typename Surface::Scratch scratch{};
        if constexpr (requires { surface_.bind_tile(rays_, target.rect, scratch); })
            if (target.rect.x0 >= target.rect.x1 || target.rect.y0 >= target.rect.y1 ||
                !surface_.bind_tile(rays_, target.rect, scratch))
                return;
        each_packet(target, scratch, [this](auto&&... a) { run_packet(a...); });
    }
    // The same packets one ray at a time, bounded by the whole surface (no tile culling):
    // march_ray, then the one-hit normal and shading. What run() is tested against (bit for
    // bit).
    void run_reference(const Tile& target) const {
        typename Surface::Scratch scratch{};
        each_packet(target, scratch, [this](auto&&... a) { run_packet_reference(a...); });
    }

private:
    template <class Packet>
    void each_packet(const Tile& target, typename Surface::Scratch& scratch, Packet packet) const {
        for (int y = target.rect.y0; y < target.rect.y1; ++y)
            for (int x = target.rect.x0; x < target.rect.x1; x += kMarchLanes) {
                const int count = std::min(kMarchLanes, target.rect.x1 - x);
                if (target.coverage && !any_active(target, x, y, count)) continue;  // tile.h
                packet(target, x, y, count, scratch);
            }
    }

    static bool any_active(const Tile& target, int x0, int y, int count) {
        for (int i = 0; i < count; ++i)
            if (target.active(x0 + i, y)) return true;
        return false;
    }

    void run_packet(const Tile& target, int x0, int y, int count, typename Surface::Scratch& scratch) const {
        using simd::vfloat;
        using simd::vmask;
        using V = simd::V3<vfloat>;
        RayPacket packet;
        rays_.packet(x0, y, count, packet);
        PacketSegments segments;
        const auto& field = surface_.bind(packet, kMiss, segments, scratch);
        const vmask live = simd::lane_index() < simd::vint(count);
        vfloat t0 = vfloat::load(segments.t0), t1 = vfloat::load(segments.t1);
        if (!simd::any(live & (t0 <= t1))) return;  // the bounds hold no ray: nothing to march
        // The march starts at the near plane, as the rasterizer clips there: a surface cut by
        // it shows what lies behind the cut. Nothing behind the stored surface can show; a
        // small margin leaves exact ties to the depth comparison below. (Lanes past `count`
        // read the first pixel's depth; they are not marched.)
        alignas(64) float stored[kMarchLanes];
        for (int i = 0; i < kMarchLanes; ++i) stored[i] = target.depth_at(x0 + (i < count ? i : 0), y);
        const V d{vfloat::load(packet.dx), vfloat::load(packet.dy), vfloat::load(packet.dz)};
        const vfloat behind = rays_.distances_from_depth(x0, y, vfloat::load(stored)) * vfloat(1.0001f);
        simd::std_max(t0, rays_.near_distances(d)).store(segments.t0);
        simd::std_min(t1, simd::std_min(behind, rays_.far_distances(d))).store(segments.t1);
        alignas(64) float t_hit[kMarchLanes];
        march_packet(field, packet, segments, settings_, t_hit);

        // Hits nearer than what is stored win the pixel; the others keep it.
        const vfloat t = vfloat::load(t_hit);
        const V o{vfloat::load(packet.ox), vfloat::load(packet.oy), vfloat::load(packet.oz)};
        const V p{o.x + d.x * t, o.y + d.y * t, o.z + d.z * t};
        // At the near plane the depth rounds to either side of 0.
        alignas(64) float depth[kMarchLanes];
        simd::std_max(rays_.window_depths(p), vfloat(0.0f)).store(depth);
        uint32_t won = 0;
        for (int i = 0; i < count; ++i) {
            if (t_hit[i] == kMiss) continue;
            float& old = target.depth_at(x0 + i, y);
            if (!(depth[i] < old)) continue;  // behind what is already there
            old = depth[i];
            if (target.triangle) target.triangle_at(x0 + i, y) = kNoTriangle;
            won |= 1u << i;
        }
        if (!won) return;

        // Every lane shades the point of a winning lane (the others' points may be at
        // infinity), so the lanes that are kept see exactly their own point.
        alignas(64) float px[kMarchLanes], py[kMarchLanes], pz[kMarchLanes];
        p.x.store(px);
        p.y.store(py);
        p.z.store(pz);
        const int first = std::countr_zero(won);
        for (int i = 0; i < kMarchLanes; ++i)
            if (!(won >> i & 1u)) px[i] = px[first], py[i] = py[first], pz[i] = pz[first];
        const V at{vfloat::load(px), vfloat::load(py), vfloat::load(pz)};
        const V n = surface_normals(field, px, py, pz, look_.normals);
        const V c = shade_surface<vfloat>(look_.material, look_.lights, background_, at, d, n);
        alignas(64) float r[kMarchLanes], g[kMarchLanes], b[kMarchLanes];
        c.x.store(r);
        c.y.store(g);
        c.z.store(b);
        for (uint32_t lanes = won; lanes; lanes &= lanes - 1) {
            const int i = std::countr_zero(lanes);
            target.colour_at(x0 + i, y) = glm::vec4(r[i], g[i], b[i], 1.0f);
        }
    }

    void run_packet_reference(const Tile& target, int x0, int y, int count,
                              typename Surface::Scratch& scratch) const {
        RayPacket packet;
        rays_.packet(x0, y, count, packet);
        PacketSegments segments;
        const auto& field = surface_.bind(packet, kMiss, segments, scratch);
        for (int i = 0; i < count; ++i) {
            const glm::vec3 d = packet.direction(i);
            const float stored = rays_.distance_from_depth(x0 + i, y, target.depth_at(x0 + i, y));
            const Interval segment{std::max(segments.t0[i], rays_.near_distance(d)),
                                   std::min(segments.t1[i], std::min(stored * 1.0001f, rays_.far_distance(d)))};
            const float t_hit = march_ray(field, packet.origin(i), d, segment, settings_);
            if (t_hit == kMiss) continue;
            const glm::vec3 p = packet.at(i, t_hit);
            const float depth = std::max(rays_.window_depth(p), 0.0f);
            float& old = target.depth_at(x0 + i, y);
            if (!(depth < old)) continue;
            old = depth;
            if (target.triangle) target.triangle_at(x0 + i, y) = kNoTriangle;
            const glm::vec3 n = surface_normal(field, p, look_.normals);
            const glm::vec3 c = shade_surface(look_.material, look_.lights, background_, p, d, n);
            target.colour_at(x0 + i, y) = glm::vec4(c, 1.0f);
        }
    }

    Surface surface_;
    const RayGenerator& rays_;
    MarchSettings settings_;
    SurfaceLook look_;
    const scene::Background& background_;
};

}  // namespace tessera::march
