#include "raster/embree/scene.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <stdexcept>

namespace tessera::embree {
namespace {

bool finite(const glm::vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

MeshDefects add(MeshDefects a, const MeshDefects& b) {
    a.nonfinite += b.nonfinite;
    a.bad_index += b.bad_index;
    a.degenerate += b.degenerate;
    return a;
}

// The defects of triangles `indices` (3 per triangle) over `positions`.
MeshDefects find_defects(std::span<const glm::vec3> positions, std::span<const uint32_t> indices) {
    const size_t vertices = positions.size();
    // Integer sums: the reduction order cannot change the result.
    return tbb::parallel_reduce(
        tbb::blocked_range<size_t>(0, indices.size() / 3, 1 << 14), MeshDefects{},
        [&](const tbb::blocked_range<size_t>& range, MeshDefects found) {
            for (size_t t = range.begin(); t != range.end(); ++t) {
                const uint32_t* index = &indices[3 * t];
                if (index[0] >= vertices || index[1] >= vertices || index[2] >= vertices) {
                    ++found.bad_index;
                    continue;
                }
                const glm::vec3& a = positions[index[0]];
                const glm::vec3& b = positions[index[1]];
                const glm::vec3& c = positions[index[2]];
                if (!finite(a) || !finite(b) || !finite(c)) {
                    ++found.nonfinite;
                    continue;
                }
                const glm::vec3 n = glm::cross(b - a, c - a);
                if (n.x == 0.0f && n.y == 0.0f && n.z == 0.0f) ++found.degenerate;
            }
            return found;
        },
        add);
}

}  // namespace

MeshDefects find_mesh_defects(const Mesh& mesh) { return find_defects(mesh.positions, mesh.indices); }

void reserve_ray_padding(Mesh& mesh) { mesh.positions.reserve(mesh.positions.size() + 1); }

RayScene::RayScene(const RayDevice& device, const Mesh& mesh, BvhUpdate update)
    : device_(&device), mesh_(&mesh) {
    if (mesh.indices.size() % 3 != 0)
        throw std::invalid_argument("mesh has " + std::to_string(mesh.indices.size()) +
                                    " indices, not a multiple of 3");
    const RTCDevice handle = device.handle();
    scene_ = rtcNewScene(handle);
    // Context filters: primary rays pass through transparent triangles, and the transparent
    // pass collects them (ray_cast.h, transparent_hits.h); rays without a filter pay nothing.
    const RTCSceneFlags flags = RTCSceneFlags(RTC_SCENE_FLAG_ROBUST | RTC_SCENE_FLAG_CONTEXT_FILTER_FUNCTION);
    rtcSetSceneFlags(scene_, flags);
    device.check("cannot create a scene");
    if (update != BvhUpdate::none) {
        rtcSetSceneFlags(scene_, RTCSceneFlags(flags | RTC_SCENE_FLAG_DYNAMIC));
        rtcSetSceneBuildQuality(scene_, RTC_BUILD_QUALITY_LOW);
    }
    if (mesh.triangle_count() > 0 && mesh.vertex_count() > 0) {
        geometry_ = rtcNewGeometry(handle, RTC_GEOMETRY_TYPE_TRIANGLE);
        rtcSetGeometryBuildQuality(geometry_, update == BvhUpdate::refit ? RTC_BUILD_QUALITY_REFIT
                                              : update == BvhUpdate::rebuild
                                                  ? RTC_BUILD_QUALITY_LOW
                                                  : RTC_BUILD_QUALITY_MEDIUM);
        shares_vertices_ = mesh.positions.capacity() > mesh.positions.size();
        if (shares_vertices_)
            rtcSetSharedGeometryBuffer(geometry_, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                       mesh.positions.data(), 0, sizeof(glm::vec3),
                                       mesh.vertex_count());
        else
            copy_positions();
        rtcSetSharedGeometryBuffer(geometry_, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                   mesh.indices.data(), 0, 3 * sizeof(uint32_t),
                                   mesh.triangle_count());
        rtcCommitGeometry(geometry_);
        rtcAttachGeometryByID(scene_, geometry_, 0);
        device.check("cannot create the triangle geometry");
    }
    defects_ = find_mesh_defects(mesh);
    commit();
}

RayScene::RayScene(const RayDevice& device, const Mesh& mesh, std::span<const MeshPart> parts)
    : device_(&device), mesh_(&mesh) {
    scene_ = rtcNewScene(device.handle());
    // DYNAMIC + LOW: Embree's two-level build, one BVH per geometry, rebuilt only when the
    // geometry was committed since (see the header).
    rtcSetSceneFlags(scene_, RTCSceneFlags(RTC_SCENE_FLAG_ROBUST | RTC_SCENE_FLAG_CONTEXT_FILTER_FUNCTION |
                                           RTC_SCENE_FLAG_DYNAMIC));
    rtcSetSceneBuildQuality(scene_, RTC_BUILD_QUALITY_LOW);
    device.check("cannot create a scene");
    try {
        update(mesh, parts);
    } catch (...) {
        for (size_t i = 0; i < parts_.size(); ++i) release_part(i);
        rtcReleaseScene(scene_);
        throw;
    }
}

RayScene::~RayScene() {
    if (geometry_) rtcReleaseGeometry(geometry_);
    for (size_t i = 0; i < parts_.size(); ++i) release_part(i);
    rtcReleaseScene(scene_);
}

void RayScene::update(const Mesh& next, std::span<const MeshPart> parts) {
    if (geometry_) throw std::logic_error("RayScene::update(next, parts) on a scene built without parts");
    if (next.indices.size() % 3 != 0)
        throw std::invalid_argument("mesh has " + std::to_string(next.indices.size()) +
                                    " indices, not a multiple of 3");
    for (const MeshPart& p : parts)
        if (p.first_vertex + p.vertex_count > next.vertex_count() ||
            p.first_triangle + p.triangle_count > next.triangle_count() || p.first_triangle > UINT32_MAX)
            throw std::invalid_argument("a mesh part lies outside the mesh");
    mesh_ = &next;
    for (size_t i = parts.size(); i < parts_.size(); ++i) release_part(i);
    parts_.resize(parts.size());
    first_triangle_.assign(std::max<size_t>(parts.size(), 1), 0);
    parts_built_ = 0;
    defects_ = {};
    for (size_t i = 0; i < parts.size(); ++i) {
        parts_built_ += build_part(i, parts[i]);
        first_triangle_[i] = uint32_t(parts[i].first_triangle);
        defects_ = add(defects_, parts_[i].defects);
    }
    commit();
}

bool RayScene::build_part(size_t i, const MeshPart& range) {
    Part& part = parts_[i];
    const glm::vec3* positions = mesh_->positions.data() + range.first_vertex;
    const uint32_t* indices = mesh_->indices.data() + 3 * range.first_triangle;
    const size_t index_count = 3 * range.triangle_count;
    // Indices local to the part; one below the part's first vertex wraps to a bad index,
    // which Embree skips and the defects count, as in a scene without parts.
    const uint32_t base = uint32_t(range.first_vertex);
    const bool resized = !part.geometry || part.range.vertex_count != range.vertex_count ||
                         part.range.triangle_count != range.triangle_count || part.range.still != range.still;
    part.range = range;
    if (!resized) {
        const auto* held_positions =
            static_cast<const glm::vec3*>(rtcGetGeometryBufferData(part.geometry, RTC_BUFFER_TYPE_VERTEX, 0));
        const auto* held_indices =
            static_cast<const uint32_t*>(rtcGetGeometryBufferData(part.geometry, RTC_BUFFER_TYPE_INDEX, 0));
        // Bytes, not values: a part is unchanged only if its BVH would be built from the same bits.
        bool same = std::memcmp(held_positions, positions, range.vertex_count * sizeof(glm::vec3)) == 0;
        for (size_t k = 0; same && k < index_count; ++k) same = indices[k] - base == held_indices[k];
        if (same) return false;
    } else {
        release_part(i);
        if (range.vertex_count == 0 || range.triangle_count == 0) {
            part.defects = {};
            return false;
        }
        part.geometry = rtcNewGeometry(device_->handle(), RTC_GEOMETRY_TYPE_TRIANGLE);
        rtcSetGeometryBuildQuality(part.geometry, range.still ? RTC_BUILD_QUALITY_MEDIUM : RTC_BUILD_QUALITY_LOW);
        // rtcSetNewGeometryBuffer pads its allocation as Embree requires.
        rtcSetNewGeometryBuffer(part.geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, sizeof(glm::vec3),
                                range.vertex_count);
        rtcSetNewGeometryBuffer(part.geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(uint32_t),
                                range.triangle_count);
        device_->check("cannot allocate a part's buffers");
    }
    auto* held_positions = static_cast<glm::vec3*>(rtcGetGeometryBufferData(part.geometry, RTC_BUFFER_TYPE_VERTEX, 0));
    auto* held_indices = static_cast<uint32_t*>(rtcGetGeometryBufferData(part.geometry, RTC_BUFFER_TYPE_INDEX, 0));
    std::memcpy(held_positions, positions, range.vertex_count * sizeof(glm::vec3));
    for (size_t k = 0; k < index_count; ++k) held_indices[k] = indices[k] - base;
    if (!resized) {
        rtcUpdateGeometryBuffer(part.geometry, RTC_BUFFER_TYPE_VERTEX, 0);
        rtcUpdateGeometryBuffer(part.geometry, RTC_BUFFER_TYPE_INDEX, 0);
    }
    rtcCommitGeometry(part.geometry);
    if (resized) rtcAttachGeometryByID(scene_, part.geometry, unsigned(i));
    device_->check("cannot create a part's triangle geometry");
    part.defects = find_defects({held_positions, range.vertex_count}, {held_indices, index_count});
    return true;
}

void RayScene::release_part(size_t i) {
    Part& part = parts_[i];
    if (!part.geometry) return;
    rtcDetachGeometry(scene_, unsigned(i));
    rtcReleaseGeometry(part.geometry);
    part.geometry = nullptr;
}

void RayScene::copy_positions() {
    // rtcSetNewGeometryBuffer pads its allocation as Embree requires.
    void* data = rtcSetNewGeometryBuffer(geometry_, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                         sizeof(glm::vec3), mesh_->vertex_count());
    device_->check("cannot allocate the vertex buffer");
    std::memcpy(data, mesh_->positions.data(), mesh_->vertex_count() * sizeof(glm::vec3));
}

void RayScene::update() {
    if (!geometry_ && !parts_.empty()) throw std::logic_error("RayScene::update() on a scene built with parts");
    if (geometry_) {
        if (!shares_vertices_)
            std::memcpy(rtcGetGeometryBufferData(geometry_, RTC_BUFFER_TYPE_VERTEX, 0),
                        mesh_->positions.data(), mesh_->vertex_count() * sizeof(glm::vec3));
        rtcUpdateGeometryBuffer(geometry_, RTC_BUFFER_TYPE_VERTEX, 0);
        rtcCommitGeometry(geometry_);
    }
    defects_ = find_mesh_defects(*mesh_);
    commit();
}

void RayScene::commit() {
    // Isolated so that Embree's build tasks never run inside (or get parented to) a caller's
    // TBB work (embree #560).
    tbb::this_task_arena::isolate([&] { rtcCommitScene(scene_); });
    device_->check("cannot build the BVH");
}

}  // namespace tessera::embree
