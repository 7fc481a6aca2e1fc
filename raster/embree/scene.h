// An Embree scene over a tessera Mesh. Built whole: one triangle geometry (geometry id 0)
// whose primitive ids are the mesh's triangle ids, built over the SAME vertex and index
// buffers the rasterizer reads (rtcSetSharedGeometryBuffer), so the two renderers see
// identical input. Built by parts: see "Animation by parts" below.
//
// Padding: Embree reads the last vertex with a 16-byte SSE load (buffer_padding.md), 4 bytes
// past a float3 array. A std::vector<glm::vec3> whose capacity exceeds its size has those
// bytes, so reserve_ray_padding() (one reserve(size + 1) where the frame's mesh is baked) is
// all sharing needs. A mesh without that capacity cannot be shared without reading out of
// bounds; only then the scene copies the positions into an Embree-allocated (padded) buffer,
// and shares_vertices() says so. Indices need no padding.
//
// Animation: the same topology with moved vertices is update()d, either by refitting the BVH
// (scene quality LOW + DYNAMIC, geometry quality REFIT: rtcSetGeometryBuildQuality.md says
// REFIT is honoured only under a LOW scene) or by a LOW-quality rebuild; bench_raytrace
// measures which wins.
//
// Animation by parts: a scene built over the mesh's parts (the objects of a baked scene) has
// one geometry per part (geometry id = part index) in a DYNAMIC scene, for which Embree builds
// two levels: a BVH per geometry, then a small one over their bounds. update(next, parts)
// compares each part of the next frame's mesh with the copy Embree holds and rebuilds only
// the parts that differ; a part that did not move keeps its BVH, so the ground of an animation
// is built once per run, not once per frame. A still part (MeshPart::still) gets a MEDIUM
// quality BVH (SAH: dearer to build, cheaper to trace, and built once), the others LOW. A
// part's BVH depends only on the part's own triangles, never on the frames before (no
// refit): a frame's bytes are the same whichever frames were rendered before it, as shards
// and --resume require. Parts mode copies the positions and indices (local to the part) into
// Embree's buffers, since the frame's mesh is gone when the next one is compared with them.
//
// Triangle ids: a hit's triangle in the mesh is triangle(geomID, primID), the part's first
// triangle plus the primitive id (just primID for a scene of one part).
//
// Robustness: scenes are built with RTC_SCENE_FLAG_ROBUST. Without it Embree's faster
// traversal missed a triangle stretched from the near plane to w = 36 whose interior covered
// the pixel centre 0.7 pixels from any edge (embree_raster_test), where the rasterizer,
// rightly, drew it; the two renderers must agree on such pixels.
//
// Bad geometry: Embree itself skips triangles with non-finite vertices or out-of-range
// indices (they are never hit), and zero-area triangles cannot be hit; the scene counts all
// three in defects() so the command can report them while the frame still renders.
#pragma once
#include <embree3/rtcore.h>

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "raster/embree/device.h"
#include "raster/core/mesh.h"

namespace tessera::embree {

enum class BvhUpdate {
    none,     // static scene: MEDIUM quality BVH (best traversal), built once
    refit,    // animated: LOW scene, REFIT geometry; update() refits the existing BVH
    rebuild,  // animated: LOW scene and geometry; update() rebuilds from scratch
};

struct MeshDefects {
    size_t nonfinite = 0;   // a vertex is NaN or infinite
    size_t bad_index = 0;   // an index is >= vertex_count
    size_t degenerate = 0;  // finite, valid indices, zero area (exactly)
    size_t total() const { return nonfinite + bad_index + degenerate; }
};

MeshDefects find_mesh_defects(const Mesh& mesh);

// Gives `mesh.positions` the capacity Embree's 16-byte read of the last vertex needs.
void reserve_ray_padding(Mesh& mesh);

class RayScene {
public:
    // The scene keeps pointers into `mesh`: the mesh must outlive the scene and its vectors
    // must not reallocate (call update() after changing positions in place).
    // Throws std::invalid_argument if the index count is not a multiple of 3, tessera::Error
    // if Embree fails.
    RayScene(const RayDevice& device, const Mesh& mesh, BvhUpdate update = BvhUpdate::none);
    // One geometry per part of `mesh` (every part's indices inside its vertex range; parts
    // need not cover the mesh), MEDIUM quality for still parts and LOW for the others, copied
    // into Embree's buffers: the scene keeps a pointer to `mesh` until the next
    // update(next, parts). Throws as above.
    RayScene(const RayDevice& device, const Mesh& mesh, std::span<const MeshPart> parts);
    ~RayScene();
    RayScene(const RayScene&) = delete;
    RayScene& operator=(const RayScene&) = delete;

    // Re-reads the mesh's positions (same counts as at construction) and refits or rebuilds
    // the BVH as chosen at construction. With BvhUpdate::none it rebuilds at MEDIUM quality.
    // Only for a scene built without parts.
    void update();
    // Parts mode: `next` (the next frame's mesh, parts as at construction or not) replaces the
    // mesh; the parts whose positions or indices changed are copied and rebuilt, the others
    // keep their BVHs.
    void update(const Mesh& next, std::span<const MeshPart> parts);

    RTCScene handle() const { return scene_; }
    const Mesh& mesh() const { return *mesh_; }
    const MeshDefects& defects() const { return defects_; }
    bool shares_vertices() const { return shares_vertices_; }
    // Parts mode: how many parts the construction or the last update built.
    size_t parts_built() const { return parts_built_; }
    // The mesh's triangle id of a hit on primitive `primitive` of geometry `geometry`.
    uint32_t triangle(unsigned geometry, unsigned primitive) const {
        return first_triangle_[geometry] + primitive;
    }

private:
    struct Part {
        MeshPart range;
        RTCGeometry geometry = nullptr;
        MeshDefects defects;
    };

    void copy_positions();
    void commit();
    // Parts mode: (re)creates or refills part i's geometry from mesh_ when it differs.
    bool build_part(size_t i, const MeshPart& range);
    void release_part(size_t i);

    const RayDevice* device_;
    const Mesh* mesh_;
    RTCScene scene_ = nullptr;
    RTCGeometry geometry_ = nullptr;  // the one geometry of a scene without parts
    std::vector<Part> parts_;         // parts mode only
    std::vector<uint32_t> first_triangle_{0};  // per geometry id
    MeshDefects defects_;
    size_t parts_built_ = 0;
    bool shares_vertices_ = false;
};

}  // namespace tessera::embree
