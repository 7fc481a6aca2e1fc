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
    for (int by = tile.y0; by < tile.y1; by += P::kHeight)
        for (int bx = tile.x0; bx < tile.x1; bx += P::kWidth) {
            typename P::RayHit packet;
            alignas(64) int valid[16];
            for (int lane = 0; lane < 16; ++lane) {
                const int x = bx + lane % P::kWidth, y = by + lane / P::kWidth;
                valid[lane] = (x < tile.x1 && y < tile.y1) ? -1 : 0;
                glm::vec3 origin(0.0f), direction(0.0f, 0.0f, 1.0f);
                if (valid[lane]) rays.pixel_ray(x, y, origin, direction);
                set_lane(packet.ray, lane, origin, direction, 0.0f, 1.0f);
                packet.hit.geomID[lane] = RTC_INVALID_GEOMETRY_ID;
            }
            hits.clear();
            P::intersect(valid, scene.handle(), &collect.context, &packet);
            for (const Hit& h : hits) {
                const int x = bx + int(h.lane) % P::kWidth, y = by + int(h.lane) / P::kWidth;
                const uint32_t* index = &mesh.indices[3 * size_t(h.triangle)];
                const PixelRays::DepthPlane plane = rays.depth_plane(
                    mesh.positions[index[0]], mesh.positions[index[1]], mesh.positions[index[2]]);
                if (!plane.valid) continue;  // seen edge-on: the rasterizer draws nothing either
                const float depth = plane.at(x + 0.5, y + 0.5);
                if (depth < opaque.depth_at(x, y) && depth >= 0.0f)
                    found.push_back({h.triangle, pipeline::Fragment{uint16_t(x), uint16_t(y), depth}});
            }
        }
    // Submission order, then row order; Embree may report a triangle referenced by several
    // BVH leaves more than once for the same ray.
    std::sort(found.begin(), found.end(), [](const Candidate& a, const Candidate& b) {
        if (a.triangle != b.triangle) return a.triangle < b.triangle;
        if (a.fragment.y != b.fragment.y) return a.fragment.y < b.fragment.y;
        return a.fragment.x < b.fragment.x;
    });
    found.erase(std::unique(found.begin(), found.end(),
                            [](const Candidate& a, const Candidate& b) {
                                return a.triangle == b.triangle && a.fragment.x == b.fragment.x &&
                                       a.fragment.y == b.fragment.y;
                            }),
                found.end());
    std::vector<pipeline::Fragment> fragments;
    for (size_t i = 0; i < found.size();) {
        const uint32_t triangle = found[i].triangle;
        fragments.clear();
        for (; i < found.size() && found[i].triangle == triangle; ++i) fragments.push_back(found[i].fragment);
        blend(triangle, fragments);
    }
}

}  // namespace tessera::embree
