#include "raster/embree/shadow_rays.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "raster/embree/packets.h"

namespace tessera::embree {
namespace {

struct ShadowRay {
    glm::vec3 origin, direction;
};

ShadowRay shadow_ray(const glm::vec3& position, const glm::vec3& normal, const glm::vec3& light) {
    const float scale = 1.0f + std::max({std::abs(position.x), std::abs(position.y),
                                         std::abs(position.z)});
    const glm::vec3 origin = position + normal * (kShadowRayOffset * scale);
    return {origin, light - origin};
}

void trace_single(RTCScene scene, const shadow::SurfacePoints& points, const glm::vec3& light,
                  uint8_t bit, std::span<uint8_t> visible) {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    for (size_t i = 0; i < points.size(); ++i) {
        if (!shadow::faces_light(points.position[i], points.normal[i], light)) continue;
        const ShadowRay r = shadow_ray(points.position[i], points.normal[i], light);
        RTCRay ray{};
        ray.org_x = r.origin.x;
        ray.org_y = r.origin.y;
        ray.org_z = r.origin.z;
        ray.dir_x = r.direction.x;
        ray.dir_y = r.direction.y;
        ray.dir_z = r.direction.z;
        ray.tnear = 0.0f;
        ray.tfar = 1.0f;
        ray.mask = 0xFFFFFFFFu;
        rtcOccluded1(scene, &context, &ray);
        if (ray.tfar >= 0.0f) visible[i] |= bit;  // an occluded ray comes back with tfar = -inf
    }
}

// The points that face the light, in order: packets are filled with them only, so no lane
// is spent on a point the light cannot reach (and consecutive points stay neighbours).
void facing_points(const shadow::SurfacePoints& points, const glm::vec3& light, uint8_t bit,
                   std::vector<uint32_t>& out) {
    out.clear();
    const bool known = points.facing.size() == points.size();  // gathered with the lights
    for (size_t i = 0; i < points.size(); ++i)
        if (known ? (points.facing[i] & bit) != 0 : shadow::faces_light(points.position[i], points.normal[i], light))
            out.push_back(uint32_t(i));
}

template <int N>
void trace_packets(RTCScene scene, const shadow::SurfacePoints& points, const glm::vec3& light,
                   uint8_t bit, std::span<uint8_t> visible) {
    using P = Packet<N>;
    RTCIntersectContext context = coherent_context();
    thread_local std::vector<uint32_t> traced;
    facing_points(points, light, bit, traced);
    for (size_t first = 0; first < traced.size(); first += N) {
        typename P::Ray packet;
        alignas(64) int valid[N];
        for (int lane = 0; lane < N; ++lane) {
            const size_t k = first + size_t(lane);
            valid[lane] = k < traced.size() ? -1 : 0;
            const ShadowRay r = valid[lane] ? shadow_ray(points.position[traced[k]], points.normal[traced[k]], light)
                                            : ShadowRay{glm::vec3(0.0f), glm::vec3(0.0f, 0.0f, 1.0f)};
            set_lane(packet, lane, r.origin, r.direction, 0.0f, 1.0f);
        }
        P::occluded(valid, scene, &context, &packet);
        for (int lane = 0; lane < N; ++lane)
            if (valid[lane] && packet.tfar[lane] >= 0.0f) visible[traced[first + size_t(lane)]] |= bit;
    }
}

}  // namespace

void trace_shadow_rays(const RayScene& scene, const shadow::SurfacePoints& points,
                       std::span<const glm::vec3> lights, std::span<uint8_t> visible,
                       RayPacket packet) {
    const FlushDenormals flush;  // Embree's per-thread recommendation (device.h)
    for (size_t l = 0; l < lights.size(); ++l) {
        const uint8_t bit = uint8_t(1u << l);
        switch (packet) {
            case RayPacket::single: trace_single(scene.handle(), points, lights[l], bit, visible); break;
            case RayPacket::x8: trace_packets<8>(scene.handle(), points, lights[l], bit, visible); break;
            case RayPacket::x16: trace_packets<16>(scene.handle(), points, lights[l], bit, visible); break;
        }
    }
}

shadow::LightTest shadow_ray_test(const RayScene& scene, RayPacket packet) {
    return [&scene, packet](const shadow::SurfacePoints& points,
                            std::span<const glm::vec3> lights, std::span<uint8_t> visible) {
        trace_shadow_rays(scene, points, lights, visible, packet);
    };
}

}  // namespace tessera::embree
