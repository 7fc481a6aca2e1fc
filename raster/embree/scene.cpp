#include "raster/embree/scene.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>
#include <tbb/task_arena.h>

#include <cmath>
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

}  // namespace

MeshDefects find_mesh_defects(const Mesh& mesh) {
    const size_t vertices = mesh.vertex_count();
    // Integer sums: the reduction order cannot change the result.
    return tbb::parallel_reduce(
        tbb::blocked_range<size_t>(0, mesh.triangle_count(), 1 << 14), MeshDefects{},
        [&](const tbb::blocked_range<size_t>& range, MeshDefects found) {
            for (size_t t = range.begin(); t != range.end(); ++t) {
                const uint32_t* index = &mesh.indices[3 * t];
                if (index[0] >= vertices || index[1] >= vertices || index[2] >= vertices) {
                    ++found.bad_index;
                    continue;
                }
                const glm::vec3& a = mesh.positions[index[0]];
                const glm::vec3& b = mesh.positions[index[1]];
                const glm::vec3& c = mesh.positions[index[2]];
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

RayScene::~RayScene() {
    if (geometry_) rtcReleaseGeometry(geometry_);
    rtcReleaseScene(scene_);
}

void RayScene::copy_positions() {
    // rtcSetNewGeometryBuffer pads its allocation as Embree requires.
    void* data = rtcSetNewGeometryBuffer(geometry_, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                         sizeof(glm::vec3), mesh_->vertex_count());
    device_->check("cannot allocate the vertex buffer");
    std::memcpy(data, mesh_->positions.data(), mesh_->vertex_count() * sizeof(glm::vec3));
}

void RayScene::update() {
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
