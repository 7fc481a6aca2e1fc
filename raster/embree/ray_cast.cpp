#include "raster/embree/ray_cast.h"

#include "raster/embree/packets.h"
#include "raster/core/coverage_layers.h"
#include "raster/core/pixel_rays.h"
#include "raster/core/tile.h"
#include "raster/pipeline/sample_pattern.h"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace tessera::embree {
namespace {

// The depth plane of the last triangle written: neighbouring pixels mostly hit the same one.
struct DepthCache {
    unsigned triangle = kNoTriangle;
    PixelRays::DepthPlane plane;
};

// An intersect context whose filter rejects hits on skipped triangles, so traversal goes on
// behind them (Embree passes the context through; it must be the first member).
struct SkipContext {
    RTCIntersectContext context;
    const RayScene* scene;
    const uint8_t* skip;
};

void skip_filter(const RTCFilterFunctionNArguments* args) {
    const auto* c = reinterpret_cast<const SkipContext*>(args->context);
    for (unsigned i = 0; i < args->N; ++i)
        if (args->valid[i] != 0 &&
            c->skip[c->scene->triangle(RTCHitN_geomID(args->hit, args->N, i), RTCHitN_primID(args->hit, args->N, i))])
            args->valid[i] = 0;
}

SkipContext make_context(const RayScene& scene, bool coherent, std::span<const uint8_t> skip) {
    SkipContext c;
    if (coherent) c.context = coherent_context();
    else rtcInitIntersectContext(&c.context);
    c.scene = &scene;
    c.skip = skip.data();
    if (!skip.empty()) c.context.filter = skip_filter;
    return c;
}

struct Frame {
    const RayScene& scene;
    const PixelRays& rays;
    VisibilityBuffer& out;
    std::span<const uint8_t> skip;
    // The sample traced: its offset from the pixel centre in pixels (sample_pattern.h) and
    // its index, or -1 for the one sample at the centre.
    float ox = 0.0f, oy = 0.0f;
    int sample = -1;

    void ray(int x, int y, glm::vec3& origin, glm::vec3& direction) const {
        if (sample < 0) rays.pixel_ray(x, y, origin, direction);
        else rays.ray(float(x) + 0.5f + ox, float(y) + 0.5f + oy, origin, direction);
    }

    // Depth from the hit triangle's plane at the sample (pixel_rays.h); from the hit
    // point only for a plane through the eye, which a ray can hit only on its edge.
    void write(int x, int y, unsigned primitive, const glm::vec3& origin,
               const glm::vec3& direction, float t, DepthCache& cache) const {
        const size_t pixel = sample < 0 ? size_t(y) * size_t(out.width) + size_t(x) : out.sample_index(x, y, sample);
        (sample < 0 ? out.triangle : out.sample_triangle)[pixel] = primitive;
        if (primitive != cache.triangle) {
            const Mesh& mesh = scene.mesh();
            const uint32_t* index = &mesh.indices[3 * size_t(primitive)];
            cache.plane = rays.depth_plane(mesh.positions[index[0]], mesh.positions[index[1]],
                                           mesh.positions[index[2]]);
            cache.triangle = primitive;
        }
        (sample < 0 ? out.depth : out.sample_depth)[pixel] =
            cache.plane.valid ? cache.plane.at(x + 0.5 + double(ox), y + 0.5 + double(oy))
                              : rays.window_depth(origin + t * direction);
    }
};

void trace_single(const Frame& frame, const TileRect& tile) {
    SkipContext skip = make_context(frame.scene, false, frame.skip);
    RTCIntersectContext& context = skip.context;
    DepthCache cache;
    for (int y = tile.y0; y < tile.y1; ++y)
        for (int x = tile.x0; x < tile.x1; ++x) {
            glm::vec3 origin, direction;
            frame.ray(x, y, origin, direction);
            RTCRayHit hit{};
            hit.ray.org_x = origin.x;
            hit.ray.org_y = origin.y;
            hit.ray.org_z = origin.z;
            hit.ray.dir_x = direction.x;
            hit.ray.dir_y = direction.y;
            hit.ray.dir_z = direction.z;
            hit.ray.tnear = 0.0f;
            hit.ray.tfar = 1.0f;
            hit.ray.mask = 0xFFFFFFFFu;
            hit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
            rtcIntersect1(frame.scene.handle(), &context, &hit);
            if (hit.hit.geomID != RTC_INVALID_GEOMETRY_ID)
                frame.write(x, y, frame.scene.triangle(hit.hit.geomID, hit.hit.primID), origin, direction,
                            hit.ray.tfar, cache);
        }
}

template <int N>
void trace_packets(const Frame& frame, const TileRect& tile) {
    using P = Packet<N>;
    SkipContext skip = make_context(frame.scene, true, frame.skip);
    RTCIntersectContext& context = skip.context;
    DepthCache cache;
    for (int by = tile.y0; by < tile.y1; by += P::kHeight)
        for (int bx = tile.x0; bx < tile.x1; bx += P::kWidth) {
            typename P::RayHit packet;
            alignas(64) int valid[N];
            glm::vec3 origin[N], direction[N];
            for (int lane = 0; lane < N; ++lane) {
                const int x = bx + lane % P::kWidth, y = by + lane / P::kWidth;
                valid[lane] = (x < tile.x1 && y < tile.y1) ? -1 : 0;
                if (valid[lane]) frame.ray(x, y, origin[lane], direction[lane]);
                else origin[lane] = direction[lane] = glm::vec3(0.0f, 0.0f, 1.0f);
                set_lane(packet.ray, lane, origin[lane], direction[lane], 0.0f, 1.0f);
                packet.hit.geomID[lane] = RTC_INVALID_GEOMETRY_ID;
            }
            P::intersect(valid, frame.scene.handle(), &context, &packet);
            for (int lane = 0; lane < N; ++lane)
                if (valid[lane] && packet.hit.geomID[lane] != RTC_INVALID_GEOMETRY_ID)
                    frame.write(bx + lane % P::kWidth, by + lane / P::kWidth,
                                frame.scene.triangle(packet.hit.geomID[lane], packet.hit.primID[lane]),
                                origin[lane], direction[lane],
                                packet.ray.tfar[lane], cache);
        }
}

}  // namespace

void cast_primary_rays(const RayScene& scene, const glm::mat4& view_projection, int width,
                       int height, VisibilityBuffer& out, RayPacket packet, std::span<const uint8_t> skip,
                       int samples) {
    const std::span<const pipeline::SampleOffset> pattern = pipeline::sample_pattern(samples);
    if (!skip.empty() && skip.size() != scene.mesh().triangle_count())
        throw std::invalid_argument("cast_primary_rays: " + std::to_string(skip.size()) + " skip flags for " +
                                    std::to_string(scene.mesh().triangle_count()) + " triangles");
    const PixelRays rays(view_projection, width, height);
    out.reset(width, height);
    if (samples > 1) {
        out.samples = samples;
        out.sample_triangle.assign(out.triangle.size() * size_t(samples), kNoTriangle);
        out.sample_depth.assign(out.depth.size() * size_t(samples), 1.0f);
    }
    parallel_for_tiles(TileGrid(width, height, kRayTileSize), [&](int, const TileRect& tile) {
        const FlushDenormals flush;  // Embree's per-thread recommendation (device.h)
        for (int s = 0; s < (samples > 1 ? samples : 1); ++s) {
            Frame frame{scene, rays, out, skip};
            if (samples > 1) {
                frame.ox = float(pattern[size_t(s)].x) * (1.0f / 16.0f);
                frame.oy = float(pattern[size_t(s)].y) * (1.0f / 16.0f);
                frame.sample = s;
            }
            switch (packet) {
                case RayPacket::single: trace_single(frame, tile); break;
                case RayPacket::x8: trace_packets<8>(frame, tile); break;
                case RayPacket::x16: trace_packets<16>(frame, tile); break;
            }
        }
        if (samples == 1) return;
        // Each pixel's main surface, as the rasterizer reports it.
        CoverageLayers layers;
        layers.build(tile, samples, nullptr, [&](int x, int y, int s, uint32_t& triangle, float& depth) {
            triangle = out.sample_triangle[out.sample_index(x, y, s)];
            depth = out.sample_depth[out.sample_index(x, y, s)];
        });
        for (int y = tile.y0; y < tile.y1; ++y) {
            const size_t from = size_t(y - tile.y0) * size_t(tile.width());
            std::copy_n(layers.primary_triangles() + from, tile.width(), &out.triangle[size_t(y) * size_t(width) + size_t(tile.x0)]);
            std::copy_n(layers.primary_depths() + from, tile.width(), &out.depth[size_t(y) * size_t(width) + size_t(tile.x0)]);
        }
    });
}

}  // namespace tessera::embree
