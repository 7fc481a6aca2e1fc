// The primitive stage for one chunk of triangles: assemble each triangle from the vertex
// stage's output, reject it when it is invalid or entirely beyond one clip plane, clip it when
// it reaches beyond near/far or the guard band (clip.h), then cull and set up each resulting
// triangle (triangle_setup.h) in submission order, and list the drawn ones for binning
// (bin.h).
#pragma once
#include <cstdint>
#include <vector>

#include "raster/core/mesh.h"
#include "raster/pipeline/bin.h"
#include "raster/pipeline/raster_options.h"
#include "raster/pipeline/triangle_setup.h"
#include "raster/pipeline/vertex_stage.h"

namespace tessera::pipeline {

// Appends a bin item per drawn triangle (or clipped piece) of triangles [first, last) to
// `items`, in submission order, and adds to the counters of `stats` (triangles, invalid,
// outside, clipped, zero_area, culled_face, no_samples, setups). Small triangles inside the
// guard band are classified kLanes at a time (triangle_setup_lanes.h) and, where consecutive
// ones mostly share a tile, binned by id with their setup deferred to the tile stage
// (deferred_setup.h); the setups of the others are appended to `setups` and their items name
// them (kStoredSetup). With `store_all`, every setup is stored (for tests and benchmarks of
// the stages alone).
void run_primitive_stage(const Mesh& mesh, const ClipVertices& vertices, const Viewport& viewport,
                         const RasterOptions& options, uint32_t first, uint32_t last, std::vector<BinItem>& items,
                         std::vector<TriangleSetup>& setups, RasterStats& stats, bool store_all = false);

}  // namespace tessera::pipeline
