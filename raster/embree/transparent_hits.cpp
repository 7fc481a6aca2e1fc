#include "raster/embree/transparent_hits.h"

#include <algorithm>
#include <vector>

#include "raster/embree/packets.h"

namespace tessera::embree {
namespace {

struct Hit {
    uint32_t triangle;
    uint32_t lane;
};

// Records hits on transparent triangles and rejects them, so traversal continues; opaque hits
// are accepted and shorten the ray, so nothing behind the opaque surface is visited for long.
struct CollectContext {
    RTCIntersectContext context;  // first: Embree hands the filter this pointer
    const RayScene* scene;
    const uint8_t* transparent;
    std::vector<Hit>* hits;
};

void collect_filter(const RTCFilterFunctionNArguments* args) {
    const auto* c = reinterpret_cast<const CollectContext*>(args->context);
    for (unsigned i = 0; i < args->N; ++i) {
        if (args->valid[i] == 0) continue;
        const uint32_t triangle =
            c->scene->triangle(RTCHitN_geomID(args->hit, args->N, i), RTCHitN_primID(args->hit, args->N, i));
        if (!c->transparent[triangle]) continue;
        c->hits->push_back({triangle, RTCRayN_id(args->ray, args->N, i)});
        args->valid[i] = 0;
    }
}

}  // namespace

void for_each_transparent_hit(const RayScene& scene, const PixelRays& rays, std::span<const uint8_t> transparent,
                              const Tile& opaque,
                              const std::function<void(uint32_t, std::span<const pipeline::Fragment>)>& blend) {
    const TileRect& tile = opaque.rect;
    using P = Packet<16>;
    std::vector<Hit> hits;
    CollectContext collect{coherent_context(), &scene, transparent.data(), &hits};
    collect.context.filter = collect_filter;
    struct Candidate {
        uint32_t triangle;
        pipeline::Fragment fragment;
    };
    std::vector<Candidate> found;
    const Mesh& mesh = scene.mesh();
    // One sample: the pixel centre. Multisampled: each sample of the layer's surface, through
    // its standard position (sample_pattern.h) as the primary rays were cast, depth-tested
    // against that sample's own depth.
    const bool multi = opaque.multisampled();
    const int samples = multi ? opaque.sample_count : 1;
    for (int s = 0; s < samples; ++s) {
        const double ox = multi ? double(opaque.sample_offsets[s].x) : 0.0;
        const double oy = multi ? double(opaque.sample_offsets[s].y) : 0.0;
        const auto wanted = [&](int x, int y) {
            return x < tile.x1 && y < tile.y1 && (!multi || (opaque.sample_mask[opaque.offset(x, y)] >> s) & 1);
        };
        for (int by = tile.y0; by < tile.y1; by += P::kHeight)
            for (int bx = tile.x0; bx < tile.x1; bx += P::kWidth) {
                typename P::RayHit packet;
                alignas(64) int valid[16];
                bool any = false;
                for (int lane = 0; lane < 16; ++lane) {
                    const int x = bx + lane % P::kWidth, y = by + lane / P::kWidth;
                    valid[lane] = wanted(x, y) ? -1 : 0;
                    any = any || valid[lane];
                    glm::vec3 origin(0.0f), direction(0.0f, 0.0f, 1.0f);
                    if (valid[lane] && !multi) rays.pixel_ray(x, y, origin, direction);
                    else if (valid[lane]) rays.ray(float(x) + 0.5f + float(ox), float(y) + 0.5f + float(oy), origin, direction);
                    set_lane(packet.ray, lane, origin, direction, 0.0f, 1.0f);
                    packet.hit.geomID[lane] = RTC_INVALID_GEOMETRY_ID;
                }
                if (!any) continue;
                hits.clear();
                P::intersect(valid, scene.handle(), &collect.context, &packet);
                for (const Hit& h : hits) {
                    const int x = bx + int(h.lane) % P::kWidth, y = by + int(h.lane) / P::kWidth;
                    const uint32_t* index = &mesh.indices[3 * size_t(h.triangle)];
                    const PixelRays::DepthPlane plane = rays.depth_plane(
                        mesh.positions[index[0]], mesh.positions[index[1]], mesh.positions[index[2]]);
                    if (!plane.valid) continue;  // seen edge-on: the rasterizer draws nothing either
                    const float depth = plane.at(x + 0.5 + ox, y + 0.5 + oy);
                    const float behind = multi ? opaque.depth_at_sample(x, y, s) : opaque.depth_at(x, y);
                    if (depth < behind && depth >= 0.0f)
                        found.push_back({h.triangle, pipeline::Fragment{uint16_t(x), uint16_t(y), depth,
                                                                        uint16_t(multi ? 1u << s : 1u)}});
                }
            }
    }
    // Submission order, then row order; Embree may report a triangle referenced by several
    // BVH leaves more than once for the same ray.
    std::sort(found.begin(), found.end(), [](const Candidate& a, const Candidate& b) {
        if (a.triangle != b.triangle) return a.triangle < b.triangle;
        if (a.fragment.y != b.fragment.y) return a.fragment.y < b.fragment.y;
        return a.fragment.x < b.fragment.x;
    });
    // One fragment per triangle and pixel: its samples' masks joined, the nearest depth.
    size_t kept = 0;
    for (size_t i = 0; i < found.size(); ++i) {
        if (kept > 0 && found[kept - 1].triangle == found[i].triangle && found[kept - 1].fragment.x == found[i].fragment.x &&
            found[kept - 1].fragment.y == found[i].fragment.y) {
            pipeline::Fragment& f = found[kept - 1].fragment;
            f.mask = uint16_t(f.mask | found[i].fragment.mask);
            f.depth = found[i].fragment.depth < f.depth ? found[i].fragment.depth : f.depth;
        } else {
            found[kept++] = found[i];
        }
    }
    found.resize(kept);
    std::vector<pipeline::Fragment> fragments;
    for (size_t i = 0; i < found.size();) {
        const uint32_t triangle = found[i].triangle;
        fragments.clear();
        for (; i < found.size() && found[i].triangle == triangle; ++i) fragments.push_back(found[i].fragment);
        blend(triangle, fragments);
    }
}

}  // namespace tessera::embree
