#include "raster/embree/shadow_rays.h"

#include <algorithm>
#include <bit>
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

// Shadow rays of points that face the light, in point order, as structure of arrays: packets
// are filled with them only, so no lane is spent on a point the light cannot reach (and
// consecutive rays stay neighbours), and a packet copies its lanes instead of gathering them.
// Made kChunk points at a time, so the rays are still in L1 when their packets copy them.
struct FacingRays {
    static constexpr size_t kChunk = 256;
    static constexpr size_t kRoom = kChunk + 16 + size_t(simd::kLanes);  // a chunk's rays, a packet's leftovers, a vector
    alignas(64) float ox[kRoom], oy[kRoom], oz[kRoom], dx[kRoom], dy[kRoom], dz[kRoom];
    alignas(64) uint32_t point[kRoom];  // the index of each ray's point
    size_t size = 0;

    // Keeps rays [first, size) as rays [0, size - first): the last packet's worth not yet traced.
    void keep_from(size_t first) {
        for (float* v : {ox, oy, oz, dx, dy, dz}) std::copy(v + first, v + size, v);
        std::copy(point + first, point + size, point);
        size -= first;
    }
};

// Appends shadow_ray() for every point in [begin, end) that faces the light (faces_light),
// simd::kLanes points at a time: positions and normals loaded as three interleaved streams,
// the same float operations (the facing test, the largest magnitude, the offset) in lanes,
// and the facing lanes appended compressed, as whole vectors (the arrays have a vector of
// room past the last ray).
void facing_rays(const shadow::SurfacePoints& points, size_t begin, size_t end, const glm::vec3& light,
                 FacingRays& out) {
    using simd::kLanes;
    using simd::vfloat;
    using simd::vint;
    using simd::vmask;
    if (begin == end) return;
    const float* position = &points.position[0].x;
    const float* normal = &points.normal[0].x;
    const vfloat lx(light.x), ly(light.y), lz(light.z);
    const vint sign_off(0x7FFFFFFF);
    const auto magnitude = [&](vfloat v) { return simd::float_of_bits(simd::bits_of(v) & sign_off); };
    const auto split = [](const float* p, vfloat& x, vfloat& y, vfloat& z) {
        vint a, b, c;
        simd::load_interleaved3(reinterpret_cast<const int32_t*>(p), a, b, c);
        x = simd::float_of_bits(a), y = simd::float_of_bits(b), z = simd::float_of_bits(c);
    };
    size_t n = out.size;
    for (size_t first = begin; first < end; first += size_t(kLanes)) {
        const vint index = simd::lane_index() + vint(int32_t(first));
        vfloat px, py, pz, nx, ny, nz;
        vmask in_range(true);
        if (end - first >= size_t(kLanes)) {
            split(position + 3 * first, px, py, pz);
            split(normal + 3 * first, nx, ny, nz);
        } else {  // the last points: lanes past them repeat the last one, and are off
            in_range = index < vint(int32_t(end));
            const vint o = simd::min(index, vint(int32_t(end - 1))) * vint(3);
            px = simd::gather(position, o), py = simd::gather(position + 1, o), pz = simd::gather(position + 2, o);
            nx = simd::gather(normal, o), ny = simd::gather(normal + 1, o), nz = simd::gather(normal + 2, o);
        }
        const vmask facing = in_range & shadow::faces_light(px, py, pz, nx, ny, nz, light);
        if (!simd::any(facing)) continue;
        // std::max({|x|, |y|, |z|}): the largest magnitude (positions are finite).
        const vfloat scale = vfloat(1.0f) + simd::max(simd::max(magnitude(px), magnitude(py)), magnitude(pz));
        const vfloat step = vfloat(kShadowRayOffset) * scale;
        const vfloat ox = px + nx * step, oy = py + ny * step, oz = pz + nz * step;
        simd::compress(facing, ox).store_unaligned(out.ox + n);
        simd::compress(facing, oy).store_unaligned(out.oy + n);
        simd::compress(facing, oz).store_unaligned(out.oz + n);
        simd::compress(facing, lx - ox).store_unaligned(out.dx + n);
        simd::compress(facing, ly - oy).store_unaligned(out.dy + n);
        simd::compress(facing, lz - oz).store_unaligned(out.dz + n);
        simd::compress(facing, index).store_unaligned(reinterpret_cast<int32_t*>(out.point + n));
        n += size_t(std::popcount(simd::bits(facing)));
    }
    out.size = n;
}

// A packet's lanes from rays[first, first + count): lanes past count (the last packet of a
// list) repeat the first ray; valid[] turns them off.
template <class PacketRay>
void set_lanes(PacketRay& packet, int width, const FacingRays& rays, size_t first, int count) {
    const float* from[6] = {rays.ox, rays.oy, rays.oz, rays.dx, rays.dy, rays.dz};
    float* to[6] = {packet.org_x, packet.org_y, packet.org_z, packet.dir_x, packet.dir_y, packet.dir_z};
    for (int a = 0; a < 6; ++a) {
        if (count == width) {
            std::copy_n(from[a] + first, width, to[a]);
        } else {
            for (int lane = 0; lane < width; ++lane) to[a][lane] = from[a][first + size_t(lane < count ? lane : 0)];
        }
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

// Packets of N consecutive facing rays (the last one of the list may hold fewer), the same
// packets whichever chunk their rays were made in.
template <int N>
void trace_packets(RTCScene scene, const shadow::SurfacePoints& points, const glm::vec3& light,
                   uint8_t bit, std::span<uint8_t> visible) {
    using P = Packet<N>;
    static_assert(N <= 16, "FacingRays keeps up to 16 rays from one chunk to the next");
    RTCIntersectContext context = coherent_context();
    thread_local FacingRays rays;
    rays.size = 0;
    const size_t count = points.size();
    for (size_t begin = 0; begin < count; begin += FacingRays::kChunk) {
        const size_t end = std::min(count, begin + FacingRays::kChunk);
        facing_rays(points, begin, end, light, rays);
        size_t first = 0;
        for (; first < rays.size && (first + N <= rays.size || end == count); first += N) {
            typename P::Ray packet;
            alignas(64) int valid[N];
            const int lanes = int(std::min<size_t>(N, rays.size - first));
            for (int lane = 0; lane < N; ++lane) valid[lane] = lane < lanes ? -1 : 0;
            set_lanes(packet, N, rays, first, lanes);
            P::occluded(valid, scene, &context, &packet);
            for (int lane = 0; lane < lanes; ++lane)
                if (packet.tfar[lane] >= 0.0f) visible[rays.point[first + size_t(lane)]] |= bit;
        }
        rays.keep_from(std::min(first, rays.size));
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
