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
#include <vector>

#include "raster/march/march.h"
#include "raster/march/march_settings.h"
#include "raster/core/tile.h"
#include "raster/march/ray_generation.h"
#include "raster/march/surface_normal.h"
#include "raster/march/surface_shading.h"
#include "raster/shade/background_radiance.h"
#include "raster/core/visibility.h"

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

    void run(const Tile& target) const {
        typename Surface::Scratch scratch{};
        for (int y = target.rect.y0; y < target.rect.y1; ++y)
            for (int x = target.rect.x0; x < target.rect.x1; x += kMarchLanes) {
                const int count = std::min(kMarchLanes, target.rect.x1 - x);
                if (target.coverage && !any_active(target, x, y, count)) continue;  // tile.h
                run_packet(target, x, y, count, scratch);
            }
    }

private:
    static bool any_active(const Tile& target, int x0, int y, int count) {
        for (int i = 0; i < count; ++i)
            if (target.active(x0 + i, y)) return true;
        return false;
    }

    void run_packet(const Tile& target, int x0, int y, int count,
                    typename Surface::Scratch& scratch) const {
        RayPacket packet;
        rays_.packet(x0, y, count, packet);
        PacketSegments segments;
        const auto& field = surface_.bind(packet, kMiss, segments, scratch);
        for (int i = 0; i < kMarchLanes; ++i) {
            const int x = x0 + (i < count ? i : 0);
            // The march starts at the near plane, as the rasterizer clips there: a surface cut
            // by it shows what lies behind the cut. Nothing behind the stored surface can show;
            // a small margin leaves exact ties to the depth comparison below.
            const glm::vec3 d = packet.direction(i);
            const float stored = rays_.distance_from_depth(x, y, target.depth_at(x, y));
            segments.t0[i] = std::max(segments.t0[i], rays_.near_distance(d));
            segments.t1[i] = std::min(segments.t1[i], std::min(stored * 1.0001f, rays_.far_distance(d)));
        }
        alignas(64) float t_hit[kMarchLanes];
        march_packet(field, packet, segments, settings_, t_hit);
        for (int i = 0; i < count; ++i) {
            if (t_hit[i] == kMiss) continue;
            const glm::vec3 p = packet.at(i, t_hit[i]);
            // At the near plane the depth rounds to either side of 0.
            const float depth = std::max(rays_.window_depth(p), 0.0f);
            float& stored = target.depth_at(x0 + i, y);
            if (!(depth < stored)) continue;  // behind what is already there
            stored = depth;
            if (target.triangle)
                target.triangle_at(x0 + i, y) =
                    kNoTriangle;
            const glm::vec3 n = surface_normal(field, p, look_.normals);
            const glm::vec3 c = shade_surface(look_.material, look_.lights, background_, p,
                                              packet.direction(i), n);
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
