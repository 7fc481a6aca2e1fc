// Embree's packet types by width, so the tracing loops are written once for 8 and 16 lanes.
// Packets must be aligned to 32/64 bytes (rtcIntersect8.md / rtcIntersect16.md): the
// RTCRay*/RTCRayHit* types carry RTC_ALIGN, which C++17 honours for automatic variables.
// Valid masks hold -1 for an active lane and 0 for an inactive one.
#pragma once
#include <embree3/rtcore.h>

#include <glm/glm.hpp>

namespace tessera::embree {

template <int N>
struct Packet;

template <>
struct Packet<8> {
    using Ray = RTCRay8;
    using RayHit = RTCRayHit8;
    static constexpr int kWidth = 4;  // 4x2 pixels: the squarest block of 8
    static constexpr int kHeight = 2;
    static void intersect(const int* valid, RTCScene scene, RTCIntersectContext* context,
                          RayHit* rays) {
        rtcIntersect8(valid, scene, context, rays);
    }
    static void occluded(const int* valid, RTCScene scene, RTCIntersectContext* context,
                         Ray* rays) {
        rtcOccluded8(valid, scene, context, rays);
    }
};

template <>
struct Packet<16> {
    using Ray = RTCRay16;
    using RayHit = RTCRayHit16;
    static constexpr int kWidth = 4;  // 4x4 pixels
    static constexpr int kHeight = 4;
    static void intersect(const int* valid, RTCScene scene, RTCIntersectContext* context,
                          RayHit* rays) {
        rtcIntersect16(valid, scene, context, rays);
    }
    static void occluded(const int* valid, RTCScene scene, RTCIntersectContext* context,
                         Ray* rays) {
        rtcOccluded16(valid, scene, context, rays);
    }
};

// Writes one lane of a packet ray (RTCRay8 or RTCRay16: same field names).
template <class PacketRay>
inline void set_lane(PacketRay& ray, int lane, const glm::vec3& origin,
                     const glm::vec3& direction, float tnear, float tfar) {
    ray.org_x[lane] = origin.x;
    ray.org_y[lane] = origin.y;
    ray.org_z[lane] = origin.z;
    ray.dir_x[lane] = direction.x;
    ray.dir_y[lane] = direction.y;
    ray.dir_z[lane] = direction.z;
    ray.tnear[lane] = tnear;
    ray.tfar[lane] = tfar;
    ray.time[lane] = 0.0f;
    ray.mask[lane] = 0xFFFFFFFFu;
    ray.id[lane] = unsigned(lane);
    ray.flags[lane] = 0;
}

inline RTCIntersectContext coherent_context() {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    return context;
}

}  // namespace tessera::embree
