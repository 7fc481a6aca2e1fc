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
// On a multisampled tile (Tile::multisampled, the layers of coverage_layers.h) the pass also
// antialiases the surface's silhouettes: the pixels whose centre result differs from a
// neighbour's (silhouette_grid.h) march a ray through each of their samples in this layer
// (the standard positions of sample_pattern.h, as the rasterizer and the ray caster use),
// shade every sample that hits in front of what the pixel held, and take the mean over the
// samples, in linear light, of those colours and the pixel's previous colour for the others:
// the resolve of coverage_layers.h, one level down. The depth and triangle stay the centre's.
// Other pixels cost what they cost with one sample, plus the ring of neighbour centres each
// tile marches once.
//
// A tile reads and writes only its own pixels and each pixel's result depends only on its
// rays, so tiles can run in parallel in any order with identical output.
#pragma once
#include <algorithm>
#include <bit>
#include <cstdint>
#include <vector>

#include "raster/march/march.h"
#include "raster/march/march_settings.h"
#include "raster/core/tile.h"
#include "raster/march/ray_generation.h"
#include "raster/march/silhouette_grid.h"
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
        if (target.rect.x0 >= target.rect.x1 || target.rect.y0 >= target.rect.y1) return;
        typename Surface::Scratch scratch{};
        Silhouettes* edges = target.multisampled() ? &silhouettes(target) : nullptr;
        bool bound = true;
        if constexpr (requires { surface_.bind_tile(rays_, target.rect, scratch); })
            bound = surface_.bind_tile(rays_, target.rect, scratch);
        // A tile whose centres meet nothing can still hold an edge at its border.
        if (bound) each_packet(target, scratch, [this, edges](auto&&... a) { run_packet(a..., edges); });
        if (edges) resolve_silhouettes(target, *edges, false);
    }
    // The same packets one ray at a time, bounded by the whole surface (no tile culling):
    // march_ray, then the one-hit normal and shading. What run() is tested against (bit for
    // bit).
    void run_reference(const Tile& target) const {
        typename Surface::Scratch scratch{};
        Silhouettes* edges = target.multisampled() ? &silhouettes(target) : nullptr;
        each_packet(target, scratch, [this, edges](auto&&... a) { run_packet_reference(a..., edges); });
        if (edges) resolve_silhouettes(target, *edges, true);
    }

private:
    // A multisampled tile's record of its centres (per thread, reused tile after tile): the
    // grid of their hits, and what the pass replaced where the centre won, so that a pixel's
    // samples that miss keep the pixel's previous colour. Then the marched samples ("jobs")
    // of the edge pixels, in pixel and sample order.
    struct Silhouettes {
        SilhouetteGrid grid;
        std::vector<glm::vec4> under_colour;  // tile pixels, where the centre won
        std::vector<float> under_depth;
        std::vector<int> x, y;
        std::vector<glm::vec2> offset;
        std::vector<float> stored;  // window depth a sample must be nearer than
        std::vector<glm::vec4> colour;
        std::vector<uint8_t> hit;
        bool any_won = false;  // some centre of the tile won: else only the ring can make edges

        void clear_jobs() {
            x.clear();
            y.clear();
            offset.clear();
            stored.clear();
        }
        void add_job(int px, int py, glm::vec2 o, float depth) {
            x.push_back(px);
            y.push_back(py);
            offset.push_back(o);
            stored.push_back(depth);
        }
        size_t jobs() const { return x.size(); }
    };

    static Silhouettes& silhouettes(const Tile& target) {
        thread_local Silhouettes s;
        const size_t area = size_t(target.width()) * size_t(target.height());
        s.grid.reset(target.width(), target.height());
        s.under_colour.resize(area);
        s.under_depth.resize(area);
        s.any_won = false;
        return s;
    }

    // The normals and shading of the points (px, py, pz) of the lanes in `won`, seen along the
    // packet's directions, into r, g, b. Every lane shades a winning lane's point (the others'
    // points may be at infinity), so the lanes that are kept see exactly their own point.
    template <class Field>
    void shade_won_lanes(const Field& field, const RayPacket& packet, uint32_t won, float* px, float* py,
                         float* pz, float* r, float* g, float* b) const {
        using simd::vfloat;
        using V = simd::V3<vfloat>;
        const int lead = std::countr_zero(won);
        for (int i = 0; i < kMarchLanes; ++i)
            if (!(won >> i & 1u)) px[i] = px[lead], py[i] = py[lead], pz[i] = pz[lead];
        const V d{vfloat::load(packet.dx), vfloat::load(packet.dy), vfloat::load(packet.dz)};
        const V at{vfloat::load(px), vfloat::load(py), vfloat::load(pz)};
        const V n = surface_normals(field, px, py, pz, look_.normals);
        const V c = shade_surface<vfloat>(look_.material, look_.lights, background_, at, d, n);
        c.x.store(r);
        c.y.store(g);
        c.z.store(b);
    }

    // Records the centre result of tile pixel (x, y) before the pass writes it.
    static void record_centre(const Tile& target, Silhouettes* edges, int x, int y, float t, bool won) {
        if (!edges) return;
        const int i = x - target.rect.x0, j = y - target.rect.y0;
        edges->grid.at(i, j) = won ? t : SilhouetteGrid::kNoHit;
        edges->any_won |= won;
        if (won) {
            const size_t p = size_t(j) * size_t(target.width()) + size_t(i);
            edges->under_colour[p] = target.colour_at(x, y);
            edges->under_depth[p] = target.depth_at(x, y);
        }
    }

    // The segment of a ray through a sample of pixel (x, y): the surface's bounds cut at the
    // near and far planes and just behind `stored` (the depth the sample must beat, as seen
    // at the pixel centre). Scalar in both paths, so both march the same segments.
    void clip_job_segments(const RayPacket& packet, const Silhouettes& s, size_t first,
                           PacketSegments& segments) const {
        for (int i = 0; i < kMarchLanes; ++i) {
            const size_t k = first + size_t(i < packet.count ? i : 0);
            const glm::vec3 d = packet.direction(i);
            const float behind = rays_.distance_from_depth(s.x[k], s.y[k], s.stored[k]) * 1.0001f;
            segments.t0[i] = std::max(segments.t0[i], rays_.near_distance(d));
            segments.t1[i] = std::min(segments.t1[i], std::min(behind, rays_.far_distance(d)));
        }
    }

    // Marches and shades jobs [first, first + count): s.hit[k] tells whether job k's ray hits
    // in front of its stored depth, s.colour[k] its shaded colour then. Ring jobs (centres of
    // the neighbours) only need the distance, in s.colour[k].x.
    void march_jobs(Silhouettes& s, size_t first, int count, bool shade, bool reference) const {
        using simd::vfloat;
        using V = simd::V3<vfloat>;
        RayPacket packet;
        rays_.sample_packet(&s.x[first], &s.y[first], &s.offset[first], count, packet);
        PacketSegments segments;
        typename Surface::Scratch whole{};  // no tile culling: rings and samples reach past the centres
        const auto& field = surface_.bind(packet, kMiss, segments, whole);
        clip_job_segments(packet, s, first, segments);
        alignas(64) float t_hit[kMarchLanes];
        if (reference)
            for (int i = 0; i < count; ++i)
                t_hit[i] = march_ray(field, packet.origin(i), packet.direction(i), Interval{segments.t0[i], segments.t1[i]},
                                     settings_);
        else
            march_packet(field, packet, segments, settings_, t_hit);
        uint32_t won = 0;
        alignas(64) float px[kMarchLanes], py[kMarchLanes], pz[kMarchLanes];
        if (reference) {
            for (int i = 0; i < count; ++i) {
                if (t_hit[i] == kMiss) continue;
                const glm::vec3 p = packet.at(i, t_hit[i]);
                if (!(std::max(rays_.window_depth(p), 0.0f) < s.stored[first + size_t(i)])) continue;
                won |= 1u << i;
                px[i] = p.x, py[i] = p.y, pz[i] = p.z;
            }
        } else {
            const V d{vfloat::load(packet.dx), vfloat::load(packet.dy), vfloat::load(packet.dz)};
            const V o{vfloat::load(packet.ox), vfloat::load(packet.oy), vfloat::load(packet.oz)};
            const vfloat t = vfloat::load(t_hit);
            const V p{o.x + d.x * t, o.y + d.y * t, o.z + d.z * t};
            alignas(64) float depth[kMarchLanes];
            simd::std_max(rays_.window_depths(p), vfloat(0.0f)).store(depth);
            p.x.store(px);
            p.y.store(py);
            p.z.store(pz);
            for (int i = 0; i < count; ++i)
                if (t_hit[i] != kMiss && depth[i] < s.stored[first + size_t(i)]) won |= 1u << i;
        }
        for (int i = 0; i < count; ++i) {
            s.hit[first + size_t(i)] = won >> i & 1u;
            s.colour[first + size_t(i)] = glm::vec4(t_hit[i]);
        }
        if (!won || !shade) return;
        if (reference) {
            for (uint32_t lanes = won; lanes; lanes &= lanes - 1) {
                const int i = std::countr_zero(lanes);
                const glm::vec3 p(px[i], py[i], pz[i]), d = packet.direction(i);
                const glm::vec3 n = surface_normal(field, p, look_.normals);
                s.colour[first + size_t(i)] = glm::vec4(shade_surface(look_.material, look_.lights, background_, p, d, n), 1.0f);
            }
            return;
        }
        alignas(64) float r[kMarchLanes], g[kMarchLanes], b[kMarchLanes];
        shade_won_lanes(field, packet, won, px, py, pz, r, g, b);  // won has no lane past count
        for (uint32_t lanes = won; lanes; lanes &= lanes - 1) {
            const int i = std::countr_zero(lanes);
            s.colour[first + size_t(i)] = glm::vec4(r[i], g[i], b[i], 1.0f);
        }
    }

    void march_all_jobs(Silhouettes& s, bool shade, bool reference) const {
        s.colour.resize(s.jobs());
        s.hit.resize(s.jobs());
        for (size_t k = 0; k < s.jobs(); k += kMarchLanes)
            march_jobs(s, k, int(std::min<size_t>(kMarchLanes, s.jobs() - k)), shade, reference);
    }

    // After the centres: the ring of neighbour centres, then the samples of the edge pixels.
    void resolve_silhouettes(const Tile& target, Silhouettes& s, bool reference) const {
        const TileRect& r = target.rect;
        const int w = r.width(), h = r.height();
        // The ring: neighbour centres inside the image, next to a pixel of this layer; marched
        // as if nothing were drawn there (the neighbour's own surfaces are its tile's business:
        // a needless edge costs samples, never a wrong colour).
        s.clear_jobs();
        const auto ring = [&](int x, int y) {
            if (x < 0 || y < 0 || x >= rays_.width() || y >= rays_.height()) return;
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    const int nx = x + dx, ny = y + dy;
                    if (nx >= r.x0 && nx < r.x1 && ny >= r.y0 && ny < r.y1 && target.active(nx, ny)) {
                        s.add_job(x, y, glm::vec2(0.0f), 1.0f);
                        return;
                    }
                }
        };
        for (int x = r.x0 - 1; x <= r.x1; ++x) ring(x, r.y0 - 1);
        for (int y = r.y0; y < r.y1; ++y) ring(r.x0 - 1, y), ring(r.x1, y);
        for (int x = r.x0 - 1; x <= r.x1; ++x) ring(x, r.y1);
        march_all_jobs(s, false, reference);
        bool any = s.any_won;
        for (size_t k = 0; k < s.jobs(); ++k) {
            s.grid.at(s.x[k] - r.x0, s.y[k] - r.y0) = s.hit[k] ? s.colour[k].x : SilhouetteGrid::kNoHit;
            any |= s.hit[k] != 0;
        }
        if (!any) return;  // every centre and neighbour missed: no edge (most of a sky)
        // Pixels of this layer that the centre pass skipped (whole packets of other layers'
        // pixels are skipped; a lane of one is marched) hold no result yet: their centres
        // missed unless recorded.
        for (int j = 0; j < h; ++j) {
            const uint8_t* coverage = target.coverage + size_t(j) * target.stride;
            float* g = &s.grid.at(0, j);
            for (int i = 0; i < w; ++i)
                g[i] = !coverage[i] ? SilhouetteGrid::kUnknown : g[i] == SilhouetteGrid::kUnknown ? SilhouetteGrid::kNoHit : g[i];
        }
        s.grid.mark_edges();
        // The samples of the edge pixels, in pixel then sample order.
        s.clear_jobs();
        for (int j = 0; j < h; ++j)
            for (int i = 0; i < w; ++i) {
                if (!s.grid.edge(i, j) || !target.coverage[size_t(j) * target.stride + size_t(i)]) continue;
                const int x = r.x0 + i, y = r.y0 + j;
                const float stored = under_depth(target, s, i, j);
                for (uint32_t m = target.sample_mask[target.offset(x, y)]; m; m &= m - 1)
                    s.add_job(x, y, target.sample_offsets[std::countr_zero(m)], stored);
            }
        march_all_jobs(s, true, reference);
        for (size_t k = 0; k < s.jobs();) {
            const int x = s.x[k], y = s.y[k];
            const glm::vec4 under = under_colour(target, s, x - r.x0, y - r.y0);
            glm::vec4 sum(0.0f);
            size_t n = 0;
            for (; k < s.jobs() && s.x[k] == x && s.y[k] == y; ++k, ++n) sum += s.hit[k] ? s.colour[k] : under;
            target.colour_at(x, y) = sum * (1.0f / float(n));
        }
    }

    static float under_depth(const Tile& target, const Silhouettes& s, int i, int j) {
        const bool won = s.grid.at(i, j) != SilhouetteGrid::kNoHit;
        return won ? s.under_depth[size_t(j) * size_t(target.width()) + size_t(i)]
                   : target.depth_at(target.rect.x0 + i, target.rect.y0 + j);
    }
    static glm::vec4 under_colour(const Tile& target, const Silhouettes& s, int i, int j) {
        const bool won = s.grid.at(i, j) != SilhouetteGrid::kNoHit;
        return won ? s.under_colour[size_t(j) * size_t(target.width()) + size_t(i)]
                   : target.colour_at(target.rect.x0 + i, target.rect.y0 + j);
    }

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

    void run_packet(const Tile& target, int x0, int y, int count, typename Surface::Scratch& scratch,
                    Silhouettes* edges) const {
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
            if (t_hit[i] == kMiss) {
                record_centre(target, edges, x0 + i, y, t_hit[i], false);
                continue;
            }
            float& old = target.depth_at(x0 + i, y);
            const bool nearer = depth[i] < old;
            record_centre(target, edges, x0 + i, y, t_hit[i], nearer);
            if (!nearer) continue;  // behind what is already there
            old = depth[i];
            if (target.triangle) target.triangle_at(x0 + i, y) = kNoTriangle;
            won |= 1u << i;
        }
        if (!won) return;

        alignas(64) float px[kMarchLanes], py[kMarchLanes], pz[kMarchLanes];
        p.x.store(px);
        p.y.store(py);
        p.z.store(pz);
        alignas(64) float r[kMarchLanes], g[kMarchLanes], b[kMarchLanes];
        shade_won_lanes(field, packet, won, px, py, pz, r, g, b);
        for (uint32_t lanes = won; lanes; lanes &= lanes - 1) {
            const int i = std::countr_zero(lanes);
            target.colour_at(x0 + i, y) = glm::vec4(r[i], g[i], b[i], 1.0f);
        }
    }

    void run_packet_reference(const Tile& target, int x0, int y, int count, typename Surface::Scratch& scratch,
                              Silhouettes* edges) const {
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
            if (t_hit == kMiss) {
                record_centre(target, edges, x0 + i, y, t_hit, false);
                continue;
            }
            const glm::vec3 p = packet.at(i, t_hit);
            const float depth = std::max(rays_.window_depth(p), 0.0f);
            float& old = target.depth_at(x0 + i, y);
            record_centre(target, edges, x0 + i, y, t_hit, depth < old);
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
