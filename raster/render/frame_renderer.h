// One animation frame of an AnimatedScene, start to finish (README "One frame, as data flows"):
// animate, bake, visibility (the tile rasterizer, or Embree primary rays), then per tile while
// it is hot: shade the visible triangles, darken what the lights cannot reach (shadows), blend
// the transparent triangles in submission order, and run the scene's compute passes
// (ray-marched terrain and metaballs, fog). The same tile function serves both renderers, so
// they differ only in how visibility was found.
//
// Shadows: each tile's visible points (shadow/surface_points.h) are tested against every light
// with Embree occlusion rays (--shadows rays, embree/shadow_rays.h) or shadow maps rendered by
// the rasterizer from each light (--shadows map, shadow/shadow_map.h: cascades fitted to the
// frame's camera, as each light's shadow_map settings ask; orthographic for a directional
// light); rays and map lookups treat a directional light as a point 10^4 units away along
// its direction. A point that faces a
// light but cannot see it is re-shaded with that light's emission Le set to zero, which is
// exactly the Blinn-Phong formula with the light's direct term removed (ambient ka La stays), so
// shadowed and lit pixels come from the same shading kernel. Points facing away from a light
// keep the kernel's smooth N.L falloff (no stair-stepped terminator on coarse meshes).
//
// Frames larger than one pass (band_layout.h) are rendered band by band: what the frame
// shares (the animated scene's bake, the BVH, the shadow maps) is built once, then each band's
// regions go through the same visibility and tile stages with the camera narrowed to them
// (camera.h region()), and each finished band is handed on (to a streaming file, to MPI rank
// 0) before the next one starts, so memory holds one band, not the frame.
//
// Deterministic: tiles never share writes and every pixel depends only on its own inputs.
#pragma once
#include <cstdint>
#include <functional>
#include <memory>
#include <string_view>
#include <vector>

#include "raster/core/frame.h"
#include "raster/pipeline/rasterizer.h"
#include "raster/shadow/shadow_map.h"
#include "raster/render/band_layout.h"
#include "raster/render/animated_scene.h"
#include "raster/render/tile_pass_times.h"

namespace tessera::render {

enum class RendererKind { raster, raytrace };
enum class ShadowMode { none, map, rays };

// Throw std::invalid_argument naming the accepted values.
RendererKind parse_renderer(std::string_view name);
ShadowMode parse_shadow_mode(std::string_view name);

// The point shadows are tested against for `light`: its position, or for a directional light
// (w = 0) a point 10^4 units away along its direction.
glm::vec3 shadow_target(const scene::Light& light);

// Every light's shadow maps for one frame (--shadows map): each light's own settings, its
// cascades fitted to `camera`, aimed at shadow_target(). `maps` that already hold one map per
// light with those settings are rendered again in place (their memory reused from frame to
// frame); otherwise they are built anew. Throws std::invalid_argument for settings out of
// range.
void build_shadow_maps(pipeline::Rasterizer& rasterizer, const Mesh& mesh, std::span<const scene::Light> lights,
                       const Camera& camera, std::vector<shadow::ShadowMap>& maps);

struct FrameStats {
    // visibility: the rasterizer's vertex, setup/bin and tile raster stages, or Embree's
    // primary rays; tiles: the per-tile work after it (shading, shadows, blending, passes),
    // wall time, broken into its passes in tile_passes (thread time, tile_pass_times.h).
    // shadow_maps: every light's maps rendered (--shadows map; their lookups are in tiles).
    double animate_ms = 0, bake_ms = 0, bvh_ms = 0, shadow_maps_ms = 0, visibility_ms = 0, tiles_ms = 0,
           total_ms = 0;
    uint64_t triangles = 0;
    uint64_t shadowed_pixels = 0;
    // Ray tracing: the objects in the BVH and how many of them had theirs built this frame
    // (the others did not move since the last frame).
    uint64_t bvh_objects = 0, bvh_objects_built = 0;
    // Shadow maps: the lights' cascades and how many were drawn this frame (the others kept
    // their depth: nothing in them moved, shadow_map.h).
    uint64_t shadow_cascades = 0, shadow_cascades_drawn = 0;
    TilePassTimes tile_passes;
    pipeline::RasterStats raster;  // the raster renderer's own counts and stage times
};

class FrameRenderer {
public:
    // Throws std::invalid_argument for a bad size, shadows with more than 4 lights or a
    // sample count other than 1, 4, 8 or 16.
    //
    // samples > 1 (MSAA): visibility per sample at the standard positions
    // (pipeline/sample_pattern.h), the rasterizer's coverage or one primary ray per sample;
    // then each distinct surface of a pixel (a triangle, or nothing: background and the
    // compute passes) is shaded once, through the same tile passes, and the results are
    // averaged by the samples they cover, in linear light (core/coverage_layers.h).
    // Transparent triangles blend over each surface at its pixel centre: their own edges
    // are not antialiased. Surfaces drawn by compute passes are found per pixel centre too,
    // so their silhouettes against the background are not either.
    FrameRenderer(AnimatedScene& scene, int width, int height, RendererKind renderer, ShadowMode shadows,
                  int samples = 1);
    ~FrameRenderer();
    FrameRenderer(const FrameRenderer&) = delete;
    FrameRenderer& operator=(const FrameRenderer&) = delete;

    // The frame at `time` seconds, linear RGBA. Throws std::invalid_argument for a frame that
    // needs bands (needs_bands()).
    Frame render(float time, FrameStats* stats = nullptr);
    // The same into `frame`, whose storage is reused when it already has the renderer's size:
    // an animation renders every frame into one buffer instead of faulting in a new one.
    void render(float time, Frame& frame, FrameStats* stats = nullptr);

    // The frame at `time` seconds as 8-bit RGBA into `rgba8` (resized to width x height x 4):
    // byte for byte encode_srgb8 (output/srgb8.h) of render()'s frame, but each tile is
    // encoded as soon as its passes are done, while its colours are in cache, and the
    // rasterizer's single-sampled tiles never go through a float frame (the toon outlines then
    // ink the encoded pixels). Returns the number of pixels with a NaN or infinite value (the
    // caller refuses to write those). Throws as render().
    size_t render_srgb8(float time, std::vector<uint8_t>& rgba8, FrameStats* stats = nullptr);

    // The frame at `time` seconds as the bands of `layout` (whose size must be the
    // renderer's): for each band b with mine(b), in increasing b, calls deliver(b, pixels)
    // with the band's layout.width x rows(b) pixels. Stats sum over the rendered regions.
    using BandFilter = std::function<bool(int band)>;
    using BandSink = std::function<void(int band, const Frame& pixels)>;
    void render_bands(float time, const BandLayout& layout, const BandFilter& mine, const BandSink& deliver,
                      FrameStats* stats = nullptr);

    // Shade only the tiles that meet rows [first, last) of render()'s frame (distributed
    // tiles: each rank shades its band and the bands are gathered); their pixels are exactly
    // those of a whole-frame render since tiles are independent. Other pixels are left
    // unshaded. Default: all rows. render_bands() ignores it (its caller picks bands).
    void set_rows(int first, int last);

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace tessera::render
