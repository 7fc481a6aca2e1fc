// What one render of the tile rasterizer is asked to do (RasterOptions) and what it counted
// and timed (RasterStats). Shared by every stage of the pipeline, so that the stages need not
// see the Rasterizer that runs them.
#pragma once
#include <glm/glm.hpp>

#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>

#include "raster/core/tile.h"
#include "raster/pipeline/triangle_setup.h"

namespace tessera::pipeline {

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
    // Samples per pixel: 1, 4, 8 or 16 (sample_pattern.h). With more than one, coverage and
    // depth are found per sample, and the passes run once per distinct surface of a pixel and
    // are resolved into the colour (coverage_layers.h); they need the colour tile.
    int samples = 1;
    // false: the frame's VisibilityBuffer is not written (left empty at the viewport's size);
    // each tile's visibility stays in its cache-resident tile buffers, which the passes read
    // through TileContext::stamps, and no pass may read or write TileContext::triangle/depth
    // (null). Saves writing 8 bytes per pixel of frame memory, and reading them back, when
    // the passes produce the output themselves (tessera raster's shading without --out-id or
    // --out-depth). Single-sampled renders with triangle ids only.
    bool frame_visibility = true;
    // With frame_visibility false: the passes get each tile's visibility row-major after all
    // (TileContext::triangle/depth, row stride tile_size; TileContext::stamps null), in a
    // per-thread tile-sized buffer the next tile reuses, which they may also write (marched
    // surfaces' depths). For passes written against rows that read nothing outside their
    // tile: the frame renderer's, unless a pass reads across tiles afterwards (outlines).
    bool tile_visibility_rows = false;
    // Multisampled: also keep every sample in VisibilityBuffer::sample_triangle/sample_depth
    // (tests, --out-id); costs 8 bytes per sample of frame memory traffic.
    bool keep_samples = false;
    // Multisampled: called once per tile with its resolved colour (the tile's rect, its first
    // pixel, the row stride in pixels) while it is still in cache, as a one-sample pass sees
    // its colour tile; render() then needs no colour buffer. Called concurrently for
    // different tiles.
    std::function<void(const TileRect&, const glm::vec4*, size_t)> resolved_tile;
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

}  // namespace tessera::pipeline
