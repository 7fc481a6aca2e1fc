// The scalar reference rasterizer the tile rasterizer is tested against, pixel for pixel: one
// triangle at a time over the whole viewport, no tiles, no SIMD, no incremental stepping.
// Coverage is the D3D11.3 rule written out directly: the int64 edge function
// E = dX*(Py - Ya) - dY*(Px - Xa) at every pixel centre, inside when E > 0 or, on a top or
// left edge (§3.4.2.1), E == 0. It shares with the fast path only the definitions that are not
// under test: the clip-space transform, clipping, snapping and the depth plane.
#pragma once
#include <glm/glm.hpp>

#include "raster/core/mesh.h"
#include "raster/pipeline/rasterizer.h"
#include "raster/pipeline/viewport.h"
#include "raster/core/visibility.h"

namespace tessera::pipeline {

// Renders the opaque triangles of `mesh` (transparent ones per options are skipped) into
// `visibility` with depth test LESS. With options.samples > 1, the rule at every sample
// position of sample_pattern.h into visibility's per-sample arrays, and each pixel's main
// surface into triangle and depth, as the tile rasterizer does.
void reference_rasterize(const Mesh& mesh, const glm::mat4& view_projection, const Viewport& viewport,
                         const RasterOptions& options, VisibilityBuffer& visibility);

}  // namespace tessera::pipeline
