// The tile rasterizer: one world-space Mesh and a view_projection in, a VisibilityBuffer (and,
// through tile passes, colour) out. Public API used by the shading, transparency, compute and
// Embree layers:
//
//   tessera::Rasterizer r;                       // keeps its scratch memory between frames
//   tessera::RasterOptions options;              // cull, tile size, transparent flags, clear
//   tessera::VisibilityBuffer vis;
//   std::vector<glm::vec4> color;                // optional, linear RGBA
//   r.render(mesh, camera.view_projection(), tessera::Viewport(w, h), options, vis,
//            {shade_pass, blend_pass}, &color);
//
// A tile pass (tile_pass.h) gets a TileContext: the tile's rectangle, its row of the
// VisibilityBuffer (triangle id + window depth), a linear RGBA colour tile, the mesh and its
// clip-space vertices, and for_each_transparent() for blending. Shading interpolates with
// perspective-correct barycentrics (barycentrics.h: triangle_barycentrics(mesh, *ctx.clip, id,
// *ctx.viewport).at(x + 0.5f, y + 0.5f, l0, l1, l2), in float or simd::vfloat lanes).
//
// Pipeline (DESIGN.md "One frame"): vertex stage (SIMD, TBB over vertices) -> per chunk of
// triangles: clip (near/far, guard band), cull, setup, bin into per-chunk tile bins (TBB over
// chunks, no locks) -> per tile (TBB over tiles): clear, rasterize the bins in submission
// order with depth LESS into cache-resident tile buffers, write visibility, run the passes.
// The result is identical for any thread count and any tile size.
#pragma once
#include <glm/glm.hpp>

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "raster/mesh.h"
#include "raster/tile_pass.h"
#include "raster/triangle_setup.h"
#include "raster/viewport.h"
#include "raster/visibility.h"

namespace tessera {

struct RasterOptions {
    CullMode cull = CullMode::none;
    int tile_size = 128;                   // pixels, power of two in 16 .. 256 (128: measured best)
    std::span<const uint8_t> transparent;  // empty, or one flag per triangle (nonzero: transparent)
    glm::vec4 clear_color{0.0f, 0.0f, 0.0f, 0.0f};
    // false: the passes write their own output and get no colour tile (TileContext::color is
    // null), which saves clearing 16 bytes per pixel per frame; render() then takes no colour.
    bool tile_color = true;
    // Depth only (shadow maps): no triangle ids are written - VisibilityBuffer::triangle is
    // left empty - and no passes or colour may be given.
    bool depth_only = false;
};

// Counts and per-stage wall times of one render (times in milliseconds).
struct RasterStats {
    uint64_t triangles = 0;     // in the mesh
    uint64_t invalid = 0;       // NaN/Inf vertex or index out of range: skipped
    uint64_t outside = 0;       // entirely beyond one clip plane
    uint64_t clipped = 0;       // cut by near/far/guard band
    uint64_t zero_area = 0;     // after snapping (also clipped pieces)
    uint64_t culled_face = 0;   // back/front culling
    uint64_t no_samples = 0;    // cover no pixel centre of the viewport
    uint64_t setups = 0;        // triangles (and clipped pieces) set up for traversal
    uint64_t bin_entries = 0;   // (tile, triangle) pairs
    uint64_t visible_pixels = 0;  // covered pixels (not counted by depth-only renders)
    double vertex_ms = 0, setup_bin_ms = 0, raster_ms = 0, passes_ms = 0, total_ms = 0;

    // Sums of the counts and times of several renders (the regions of one large frame).
    RasterStats& operator+=(const RasterStats& r) {
        triangles += r.triangles, invalid += r.invalid, outside += r.outside, clipped += r.clipped;
        zero_area += r.zero_area, culled_face += r.culled_face, no_samples += r.no_samples;
        setups += r.setups, bin_entries += r.bin_entries, visible_pixels += r.visible_pixels;
        vertex_ms += r.vertex_ms, setup_bin_ms += r.setup_bin_ms, raster_ms += r.raster_ms;
        passes_ms += r.passes_ms, total_ms += r.total_ms;
        return *this;
    }
};

class Rasterizer {
public:
    Rasterizer();
    ~Rasterizer();
    Rasterizer(const Rasterizer&) = delete;
    Rasterizer& operator=(const Rasterizer&) = delete;

    // Renders `mesh` (its triangle ids are their order in mesh.indices). `visibility` is resized
    // to the viewport; `color`, when given, is resized to width*height and receives the tile
    // colour after the passes. Throws std::invalid_argument for bad options or a mesh too large
    // to index (more than 2^31 vertices or triangles).
    void render(const Mesh& mesh, const glm::mat4& view_projection, const Viewport& viewport,
                const RasterOptions& options, VisibilityBuffer& visibility,
                std::span<const TilePass> passes = {}, std::vector<glm::vec4>* color = nullptr,
                RasterStats* stats = nullptr);

    // The clip-space vertices of the last render (for barycentrics.h).
    const ClipVertices& clip_vertices() const;

private:
    struct State;
    std::unique_ptr<State> state_;
};

}  // namespace tessera
