#include "raster/pipeline/rasterizer.h"

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <bit>
#include <string>
#include <chrono>
#include <cstring>

#include "raster/core/coverage_layers.h"
#include "raster/pipeline/bin.h"
#include "raster/pipeline/deferred_setup.h"
#include "raster/pipeline/primitive_stage.h"
#include "raster/core/trace.h"

namespace tessera::pipeline {

namespace {


// Per-thread storage of the primitive stage: a chunk's bin items and stored setups until they
// are binned, and binning's counters; reused chunk after chunk, so they stay in cache.
struct ChunkScratch {
    std::vector<BinItem> items;
    std::vector<TriangleSetup> setups;
    std::vector<uint32_t> count;
};

// Per-thread storage of the tile stage, reused across tiles and frames.
struct TileScratch {
    TileBuffers buffers;
    std::vector<glm::vec4> color;
    std::vector<Fragment> fragments;
    CoverageLayers layers;  // multisampled renders
};

// A multisampled tile out of its buffers: its surfaces listed as layers, the main surface of
// each pixel (layer 0) into the frame's visibility, every sample too when kept; the buffers
// are left cleared for the next tile. `drawn`: some triangle was rasterized into the buffers;
// if none was, every sample still holds the cleared values, one surface for the whole tile
// (the sky over a landscape, or a frame that only passes draw), listed without reading them.
// Else the sample planes leave the stamp layout as row-major planes first (as flush() moves
// a one-sample tile), which the layers then read plane by plane.
void multisampled_tile(TileBuffers& buffers, const TileRect& rect, VisibilityBuffer& visibility, bool keep_samples,
                       bool drawn, CoverageLayers& layers) {
    const int samples = buffers.samples;
    const int w = rect.width(), h = rect.height();
    const size_t area = size_t(w) * size_t(h);
    thread_local AlignedVector<uint32_t> ids;
    thread_local AlignedVector<float> depths;
    const uint32_t clear_id = buffers.triangle[0];  // what an undrawn tile holds everywhere
    const float clear_depth = window_depth(buffers.depth[0]);
    if (drawn) {
        ids.resize(area * size_t(samples));
        depths.resize(area * size_t(samples));
        buffers.flush_planes(w, h, ids.data(), depths.data());
        layers.build_planes(rect, samples, sample_positions(samples), ids.data(), depths.data());
    } else {
        layers.build_uniform(rect, samples, sample_positions(samples), clear_id, clear_depth);
    }
    if (keep_samples)
        for (int y = rect.y0; y < rect.y1; ++y)
            for (int x = rect.x0; x < rect.x1; ++x) {
                const size_t p = size_t(y - rect.y0) * size_t(w) + size_t(x - rect.x0);
                for (int s = 0; s < samples; ++s) {
                    const size_t at = visibility.sample_index(x, y, s);
                    visibility.sample_triangle[at] = drawn ? ids[size_t(s) * area + p] : clear_id;
                    visibility.sample_depth[at] = drawn ? depths[size_t(s) * area + p] : clear_depth;
                }
            }
    // Layer 0 into the frame's visibility, which no pass of this tile reads (they read the
    // layers): streamed, as flush() streams a tile nothing reads again soon.
    const size_t origin = size_t(rect.y0) * size_t(visibility.width) + size_t(rect.x0);
    for (int y = 0; y < h; ++y) {
        const size_t to = origin + size_t(y) * size_t(visibility.width), from = size_t(y) * size_t(w);
        simd::stream_copy(visibility.triangle.data() + to, layers.primary_triangles() + from, size_t(w));
        simd::stream_copy(reinterpret_cast<uint32_t*>(visibility.depth.data() + to),
                          reinterpret_cast<const uint32_t*>(layers.primary_depths() + from), size_t(w));
    }
    simd::stream_fence();
}

}  // namespace

struct Rasterizer::State {
    ClipVertices vertices;
    std::vector<ChunkBins> chunks;
    std::vector<RasterStats> chunk_stats;
    tbb::enumerable_thread_specific<ChunkScratch> chunk_scratch;
    tbb::enumerable_thread_specific<TileScratch> scratch;
    TileGrid grid;
};

// What for_each_transparent needs to find one tile's triangles again.
struct TileWork {
    const std::vector<ChunkBins>* chunks;
    const SetupSource* source;
    int tile;
    std::vector<Fragment>* fragments;
};

void TileContext::for_each_transparent(
    const std::function<void(uint32_t, std::span<const Fragment>)>& blend) const {
    std::vector<Fragment>& fragments = *work->fragments;
    const size_t capacity = size_t(width()) * size_t(height()) + simd::kLanes;
    if (fragments.size() < capacity) fragments.resize(capacity);
    for (const ChunkBins& chunk : *work->chunks)
        for_each_setup(chunk, work->tile, *work->source, [&](const TriangleSetup& t) {
            if (!t.transparent) return;
            const size_t n = multisampled() ? rasterize_tested_samples(t, *this, fragments.data())
                                            : rasterize_tested(t, rect, depth, stride, fragments.data());
            if (n) blend(t.triangle, std::span<const Fragment>(fragments.data(), n));
        });
}

Rasterizer::Rasterizer() : state_(std::make_unique<State>()) {}
Rasterizer::~Rasterizer() = default;

const ClipVertices& Rasterizer::clip_vertices() const { return state_->vertices; }

void Rasterizer::render(const Mesh& mesh, const glm::mat4& view_projection, const Viewport& viewport,
                        const RasterOptions& options, VisibilityBuffer& visibility,
                        std::span<const TilePass> passes, std::vector<glm::vec4>* color,
                        RasterStats* stats) {
    const auto start = Clock::now();
    State& s = *state_;
    const size_t triangle_count = mesh.triangle_count();
    if (mesh.vertex_count() >= (size_t(1) << 31) || triangle_count >= (size_t(1) << 31))
        throw std::invalid_argument("mesh too large: at most 2^31 - 1 vertices and triangles");
    if (!options.transparent.empty() && options.transparent.size() != triangle_count)
        throw std::invalid_argument("RasterOptions::transparent must be empty or hold one flag per triangle");
    if (options.tile_size < 16 || options.tile_size > 256 || !std::has_single_bit(unsigned(options.tile_size)))
        throw std::invalid_argument("tile size " + std::to_string(options.tile_size) +
                                    " must be a power of two in 16 .. 256");
    if (!valid_sample_count(options.samples))
        throw std::invalid_argument("RasterOptions::samples must be 1, 4, 8 or 16, not " + std::to_string(options.samples));
    const int samples = options.samples;
    if (samples > 1 && (options.depth_only || !options.tile_color))
        throw std::invalid_argument("Rasterizer::render: multisampling needs the colour tile and triangle ids");
    s.grid = TileGrid(viewport.width, viewport.height, options.tile_size);
    const TileGrid& grid = s.grid;

    // Vertex stage.
    {
        TraceScope trace("vertex stage");
        run_vertex_stage(mesh, view_projection, viewport, s.vertices);
    }
    const double vertex_ms = ms_since(start);

    // Primitive stage and binning, per chunk of triangles in parallel.
    const auto setup_start = Clock::now();
    const size_t chunk_size = std::clamp<size_t>(triangle_count / 64, 4096, 65536);
    const size_t chunk_count = (triangle_count + chunk_size - 1) / chunk_size;
    s.chunks.resize(chunk_count);
    s.chunk_stats.assign(chunk_count, RasterStats{});
    tbb::parallel_for(tbb::blocked_range<size_t>(0, chunk_count, 1), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t c = r.begin(); c != r.end(); ++c) {
            TraceScope trace("setup+bin chunk", "chunk", int(c));
            ChunkBins& chunk = s.chunks[c];
            ChunkScratch& scratch = s.chunk_scratch.local();
            scratch.items.clear();
            scratch.setups.clear();
            const uint32_t first = uint32_t(c * chunk_size);
            const uint32_t last = uint32_t(std::min(triangle_count, (c + 1) * chunk_size));
            run_primitive_stage(mesh, s.vertices, viewport, options, first, last, scratch.items, scratch.setups,
                                s.chunk_stats[c]);
            chunk.bin(scratch.items, scratch.setups, grid, scratch.count);
        }
    });
    const double setup_bin_ms = ms_since(setup_start);

    // Tile stage: rasterize, write visibility, run the passes.
    const auto raster_start = Clock::now();
    visibility.width = viewport.width;
    visibility.height = viewport.height;
    if (options.depth_only && (color || !passes.empty()))
        throw std::invalid_argument("Rasterizer::render: a depth-only render takes no passes or colour");
    if (!options.frame_visibility && (options.depth_only || samples > 1))
        throw std::invalid_argument("Rasterizer::render: visibility kept in the tiles needs one sample and triangle ids");
    const bool frame_visibility = options.frame_visibility;
    if (options.depth_only || !frame_visibility) visibility.triangle.clear();
    else visibility.triangle.resize(size_t(viewport.width) * viewport.height);
    if (frame_visibility) visibility.depth.resize(size_t(viewport.width) * viewport.height);
    else visibility.depth.clear();
    if (color && !options.tile_color)
        throw std::invalid_argument("Rasterizer::render: a colour buffer needs RasterOptions::tile_color");
    if (color) color->resize(size_t(viewport.width) * viewport.height);
    visibility.samples = samples;
    const bool keep_samples = samples > 1 && options.keep_samples;
    visibility.sample_triangle.resize(keep_samples ? visibility.triangle.size() * size_t(samples) : 0);
    visibility.sample_depth.resize(keep_samples ? visibility.depth.size() * size_t(samples) : 0);
    const bool run_passes = color || !passes.empty();
    const SetupSource source{&mesh, &s.vertices, &viewport, &options};
    std::atomic<uint64_t> visible_pixels{0};
    std::atomic<int64_t> pass_ns{0};
    parallel_for_tiles(grid, [&](int tile, const TileRect& rect) {
        TileScratch& scratch = s.scratch.local();
        TraceScope trace("raster tile", "tile", rect.x0, rect.y0);
        TileBuffers& buffers = scratch.buffers;
        // Else flush() or the multisampled path below cleared them.
        if (buffers.size != grid.size || buffers.samples != samples) buffers.clear(grid.size, samples);
        bool drawn = false;
        for (const ChunkBins& chunk : s.chunks)
            for_each_setup(chunk, tile, source, [&](const TriangleSetup& t) {
                if (t.transparent) return;
                drawn = true;
                if (options.depth_only) rasterize_depth(t, rect, buffers);
                else rasterize_opaque(t, rect, buffers);
            });

        const int w = rect.width(), h = rect.height();
        const size_t origin = size_t(rect.y0) * viewport.width + rect.x0;
        const auto context_for = [&](const Tile& tile, TileWork& work) {
            TileContext context;
            static_cast<Tile&>(context) = tile;
            context.viewport = &viewport;
            context.mesh = &mesh;
            context.clip = &s.vertices;
            context.work = &work;
            return context;
        };
        if (samples > 1) {
            multisampled_tile(buffers, rect, visibility, keep_samples, drawn, scratch.layers);
            if (stats) visible_pixels += scratch.layers.covered_pixels();
            if (!run_passes) return;
            // The passes once per layer of distinct surfaces, resolved into the colour tile.
            const auto pass_start = Clock::now();
            scratch.color.resize(size_t(grid.size) * grid.size);
            TileWork work{&s.chunks, &source, tile, &scratch.fragments};
            for (int j = 0; j < scratch.layers.layers(); ++j) {
                const TileContext context = context_for(
                    scratch.layers.layer(j, options.clear_color, scratch.color.data(), size_t(grid.size)), work);
                for (const TilePass& pass : passes) pass(context);
                scratch.layers.accumulate();
            }
            if (options.resolved_tile) options.resolved_tile(rect, scratch.color.data(), size_t(grid.size));
            if (color)
                for (int y = 0; y < h; ++y)
                    std::memcpy(color->data() + size_t(rect.y0 + y) * viewport.width + rect.x0,
                                scratch.color.data() + size_t(y) * grid.size, size_t(w) * sizeof(glm::vec4));
            if (stats) pass_ns += std::chrono::duration_cast<std::chrono::nanoseconds>(Clock::now() - pass_start).count();
            return;
        }

        if (!frame_visibility) {
            // The visibility stays in the tile buffers: the passes read them there, then
            // they are cleared for the next tile.
            if (stats) visible_pixels += buffers.covered_pixels(w, h);
            if (run_passes) {
                const auto pass_start = Clock::now();
                TileWork work{&s.chunks, &source, tile, &scratch.fragments};
                Tile tile_part;
                tile_part.rect = rect;
                if (options.tile_color) {
                    scratch.color.assign(size_t(grid.size) * grid.size, options.clear_color);
                    tile_part.colour = scratch.color.data();
                    tile_part.colour_stride = size_t(grid.size);
                }
                TileContext context = context_for(tile_part, work);
                context.stamps = &buffers;
                for (const TilePass& pass : passes) pass(context);
                if (color)
                    for (int y = 0; y < h; ++y)
                        std::memcpy(color->data() + size_t(rect.y0 + y) * viewport.width + rect.x0,
                                    scratch.color.data() + size_t(y) * grid.size, size_t(w) * sizeof(glm::vec4));
                if (stats) pass_ns += std::chrono::duration_cast<std::chrono::nanoseconds>(Clock::now() - pass_start).count();
            }
            buffers.clear(grid.size, samples);
            return;
        }

        // Visibility out: stamp-swizzled tile to row-major frame.
        // Without passes nothing reads the tile again during the frame: stream it out.
        buffers.flush(w, h, options.depth_only ? nullptr : visibility.triangle.data() + origin,
                      visibility.depth.data() + origin, size_t(viewport.width), !run_passes);
        if (stats && !options.depth_only) {
            uint64_t visible = 0;
            for (int y = 0; y < h; ++y)
                for (int x = 0; x < w; ++x)
                    visible += visibility.triangle[origin + size_t(y) * viewport.width + x] != kNoTriangle;
            visible_pixels += visible;
        }
        if (!run_passes) return;

        const auto pass_start = Clock::now();
        if (options.tile_color) scratch.color.assign(size_t(grid.size) * grid.size, options.clear_color);
        TileWork work{&s.chunks, &source, tile, &scratch.fragments};
        Tile frame_part;
        frame_part.rect = rect;
        frame_part.triangle = visibility.triangle.data() + origin;
        frame_part.depth = visibility.depth.data() + origin;
        frame_part.stride = size_t(viewport.width);
        frame_part.colour = options.tile_color ? scratch.color.data() : nullptr;
        frame_part.colour_stride = size_t(grid.size);
        const TileContext context = context_for(frame_part, work);
        for (const TilePass& pass : passes) pass(context);
        if (color) {
            // Streamed out: nothing reads the frame's colour before the tiles are done, and
            // non-temporal stores save reading each destination line first.
            for (int y = 0; y < h; ++y)
                simd::stream_copy(reinterpret_cast<uint32_t*>(color->data() + size_t(rect.y0 + y) * viewport.width + rect.x0),
                                  reinterpret_cast<const uint32_t*>(scratch.color.data() + size_t(y) * grid.size),
                                  size_t(w) * 4);
            simd::stream_fence();
        }
        if (stats) pass_ns += std::chrono::duration_cast<std::chrono::nanoseconds>(Clock::now() - pass_start).count();
    });

    if (stats) {
        RasterStats total;
        for (const RasterStats& c : s.chunk_stats) {
            total.triangles += c.triangles;
            total.invalid += c.invalid;
            total.outside += c.outside;
            total.clipped += c.clipped;
            total.zero_area += c.zero_area;
            total.culled_face += c.culled_face;
            total.no_samples += c.no_samples;
            total.setups += c.setups;
        }
        for (const ChunkBins& chunk : s.chunks) total.bin_entries += chunk.entries.size();
        total.visible_pixels = visible_pixels;
        total.vertex_ms = vertex_ms;
        total.setup_bin_ms = setup_bin_ms;
        // Pass time is summed over threads; report it as wall-time share of the tile stage.
        const double tile_ms = ms_since(raster_start);
        const double pass_ms = double(pass_ns.load()) * 1e-6 / std::max(1, tbb::this_task_arena::max_concurrency());
        total.passes_ms = std::min(pass_ms, tile_ms);
        total.raster_ms = tile_ms - total.passes_ms;
        total.total_ms = ms_since(start);
        *stats = total;
    }
}

}  // namespace tessera::pipeline
