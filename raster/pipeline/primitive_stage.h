// The primitive stage for one chunk of triangles: assemble each triangle from the vertex
// stage's output, reject it when it is invalid or entirely beyond one clip plane, clip it when
// it reaches beyond near/far or the guard band (clip.h), then cull and set up each resulting
// triangle (triangle_setup.h) in submission order.
#pragma once
#include <cstdint>
#include <vector>

#include "raster/core/mesh.h"
#include "raster/pipeline/raster_options.h"
#include "raster/pipeline/triangle_setup.h"
#include "raster/pipeline/vertex_stage.h"

namespace tessera::pipeline {

// Appends the setups of triangles [first, last) to `out` and adds to the counters of `stats`
// (triangles, invalid, outside, clipped, zero_area, culled_face, no_samples, setups).
void run_primitive_stage(const Mesh& mesh, const ClipVertices& vertices, const Viewport& viewport,
                         const RasterOptions& options, uint32_t first, uint32_t last,
                         std::vector<TriangleSetup>& out, RasterStats& stats);

}  // namespace tessera::pipeline
