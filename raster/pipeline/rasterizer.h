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
// Pipeline (README "One frame, as data flows"): vertex stage (SIMD, TBB over vertices) -> per
// chunk of triangles: clip (near/far, guard band), cull, setup, bin into per-chunk tile bins
// (TBB over chunks, no locks) -> per tile (TBB over tiles): clear, rasterize the bins in
// submission order with depth LESS into cache-resident tile buffers, write visibility, run the
// passes. The result is identical for any thread count and any tile size.
#pragma once
#include <glm/glm.hpp>

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "raster/core/mesh.h"
#include "raster/pipeline/raster_options.h"
#include "raster/pipeline/tile_pass.h"
#include "raster/pipeline/triangle_setup.h"
#include "raster/pipeline/viewport.h"
#include "raster/core/visibility.h"

namespace tessera::pipeline {

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

}  // namespace tessera::pipeline
