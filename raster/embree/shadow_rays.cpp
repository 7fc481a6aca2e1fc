#include "raster/embree/shadow_rays.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "raster/embree/packets.h"
#include "raster/simd/simd.h"

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
    out.resize(points.size());
    size_t n = 0;
    if (points.facing.size() == points.size()) {  // gathered with the lights: branch-free
        const uint8_t* facing = points.facing.data();
        uint32_t* to = out.data();
        for (size_t i = 0; i < points.size(); ++i) {
            to[n] = uint32_t(i);
            n += (facing[i] & bit) != 0;
        }
    } else {
        for (size_t i = 0; i < points.size(); ++i)
            if (shadow::faces_light(points.position[i], points.normal[i], light)) out[n++] = uint32_t(i);
    }
    out.resize(n);
}

// shadow_ray() for the lanes of a packet, kLanes at a time: the points' positions and normals
// gathered, the same float operations (max of the magnitudes, then the offset), stored into
// the packet's arrays.
template <class PacketRay>
void set_lanes(PacketRay& packet, int width, const shadow::SurfacePoints& points, const uint32_t* index, int count,
               const glm::vec3& light) {
    using simd::vfloat;
    using simd::vint;
    const float* position = &points.position[0].x;
    const float* normal = &points.normal[0].x;
    const vint sign_off(0x7FFFFFFF);
    const auto magnitude = [&](vfloat v) { return simd::float_of_bits(simd::bits_of(v) & sign_off); };
    for (int first = 0; first < width; first += simd::kLanes) {
        alignas(64) int32_t offset[simd::kLanes];
        for (int lane = 0; lane < simd::kLanes; ++lane) {
            const int k = first + lane;
            offset[lane] = int32_t(3 * index[k < count ? k : 0]);  // idle lanes repeat the first ray
        }
        const vint o = vint::load(offset);
        const vfloat px = simd::gather(position, o), py = simd::gather(position + 1, o),
                     pz = simd::gather(position + 2, o);
        const vfloat nx = simd::gather(normal, o), ny = simd::gather(normal + 1, o), nz = simd::gather(normal + 2, o);
        // std::max({|x|, |y|, |z|}): the largest magnitude (positions are finite).
        const vfloat scale = vfloat(1.0f) + simd::max(simd::max(magnitude(px), magnitude(py)), magnitude(pz));
        const vfloat step = vfloat(kShadowRayOffset) * scale;
        const vfloat ox = px + nx * step, oy = py + ny * step, oz = pz + nz * step;
        // A packet narrower than the lanes (RTCRay8 with 16 AVX-512 lanes) takes only its
        // width, through an aligned copy: its arrays hold `width` floats, aligned to 32 bytes.
        const int lanes = std::min(simd::kLanes, width - first);
        const auto put = [&](vfloat v, float* array) {
            if (lanes == simd::kLanes) {
                v.store(array + first);
            } else {
                alignas(64) float all[simd::kLanes];
                v.store(all);
                std::copy_n(all, lanes, array + first);
            }
        };
        put(ox, packet.org_x);
        put(oy, packet.org_y);
        put(oz, packet.org_z);
        put(vfloat(light.x) - ox, packet.dir_x);
        put(vfloat(light.y) - oy, packet.dir_y);
        put(vfloat(light.z) - oz, packet.dir_z);
    }
    for (int lane = 0; lane < width; ++lane) {
        packet.tnear[lane] = 0.0f;
        packet.tfar[lane] = 1.0f;
        packet.time[lane] = 0.0f;
        packet.mask[lane] = 0xFFFFFFFFu;
        packet.id[lane] = unsigned(lane);
        packet.flags[lane] = 0;
    }
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
        const int count = int(std::min<size_t>(N, traced.size() - first));
        for (int lane = 0; lane < N; ++lane) valid[lane] = lane < count ? -1 : 0;
        set_lanes(packet, N, points, traced.data() + first, count, light);
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
