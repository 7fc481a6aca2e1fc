#include "raster/render/frame_renderer.h"

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <chrono>
#include <functional>
#include <memory>
#include <span>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "raster/core/coverage_layers.h"
#include "raster/embree/device.h"
#include "raster/core/pixel_rays.h"
#include "raster/core/tile.h"
#include "raster/embree/ray_cast.h"
#include "raster/embree/scene.h"
#include "raster/embree/shadow_rays.h"
#include "raster/embree/transparent_hits.h"
#include "raster/march/fog_pass.h"
#include "raster/march/march_surface.h"
#include "raster/march/metaball_orbits.h"
#include "raster/march/procedural_surfaces.h"
#include "raster/march/surface_pass.h"
#include "raster/output/srgb8.h"
#include "raster/render/layer_split.h"
#include "raster/shade/alpha_test.h"
#include "raster/shade/frame_shading.h"
#include "raster/shade/outline.h"
#include "raster/shadow/light_mask.h"
#include "raster/shadow/shadow_edges.h"
#include "raster/shadow/shadow_map.h"
#include "raster/shadow/surface_points.h"
#include "raster/core/trace.h"

namespace tessera::render {

RendererKind parse_renderer(std::string_view name) {
    if (name == "raster") return RendererKind::raster;
    if (name == "raytrace") return RendererKind::raytrace;
    throw std::invalid_argument("--renderer: unknown renderer '" + std::string(name) + "' (expected raster or raytrace)");
}

ShadowMode parse_shadow_mode(std::string_view name) {
    if (name == "none") return ShadowMode::none;
    if (name == "map") return ShadowMode::map;
    if (name == "rays") return ShadowMode::rays;
    throw std::invalid_argument("--shadows: unknown mode '" + std::string(name) + "' (expected none, map or rays)");
}

namespace {


// A directional light's stand-in point (shadow_target): far beyond any scene here, so the
// rays are parallel to within 1e-4 rad.
constexpr float kDistantLight = 1.0e4f;

// Triangles by how visibility treats them (FrameState::transparent).
constexpr uint8_t kOpaque = 0, kBlended = 1, kAlphaTested = 2;

}  // namespace

glm::vec3 shadow_target(const scene::Light& light) {
    const glm::vec3 p(light.position);
    return light.position.w == 0.0f ? glm::normalize(p) * kDistantLight : p;
}

void build_shadow_maps(pipeline::Rasterizer& rasterizer, const Mesh& mesh, std::span<const scene::Light> lights,
                       const Camera& camera, std::vector<shadow::ShadowMap>& maps) {
    bool reuse = maps.size() == lights.size();
    for (size_t l = 0; reuse && l < lights.size(); ++l) reuse = maps[l].options() == lights[l].shadow_map;
    if (!reuse) {
        maps.clear();
        maps.reserve(lights.size());
    }
    for (size_t l = 0; l < lights.size(); ++l) {
        const shadow::ShadowLight light(shadow_target(lights[l]), lights[l].position.w == 0.0f);  // w = 0: directional
        if (reuse)
            maps[l].render(rasterizer, mesh, light, &camera);
        else
            maps.emplace_back(rasterizer, mesh, light, camera, lights[l].shadow_map);
    }
}

// What every region of one frame shares, built once per frame: the animated scene baked, the
// BVH (kept by the renderer, see Impl::rays), the lights' shadow tests, the metaballs at this
// time.
struct FrameState {
    const scene::BakedScene* baked = nullptr;  // Impl::baker's
    const embree::RayScene* rays = nullptr;
    std::vector<glm::vec3> light_targets;
    shadow::LightTest light_test;
    std::vector<march::MetaballField> metaballs;
    // Per triangle, kOpaque, kBlended or kAlphaTested (both left out of the opaque pass);
    // empty when every material is opaque.
    std::vector<uint8_t> transparent;
};

// A part of the frame rendered in one pass: the whole frame, or a region of a band.
struct Region {
    Camera camera;  // narrowed to the region (camera.h region())
    int width, height;
};

// What the tile passes of one region read, built once per region: the shading (and one per
// subset of lit lights, bit l set: light l reaches the point), the rays through its pixels,
// and the scene's compute passes seen through its camera.
struct RegionPasses {
    shade::FrameShading shading;
    std::vector<std::unique_ptr<shade::FrameShading>> subset_shading;  // empty: no shadows
    uint32_t all_lit = 0;
    PixelRays pixel_rays;
    march::RayGenerator march_rays;
    struct ComputePass {
        TilePass kind;
        std::function<void(const Tile&)> run;
    };
    std::vector<ComputePass> compute;

    // rasterized: the rasterizer's vertices when it finds the region's visibility
    // (shade::RenderState::rasterized), null for rays.
    RegionPasses(const AnimatedScene& scene, const FrameState& frame, const Region& region,
                 std::span<const procedural::TerrainField> terrains, const pipeline::ClipVertices* rasterized);
};

struct FrameRenderer::Impl {
    AnimatedScene& scene;
    int width, height;
    RendererKind renderer;
    ShadowMode shadows;
    int samples;
    pipeline::Rasterizer rasterizer;
    std::optional<embree::RayDevice> device;
    // The BVH of the baked scene, one part per object, kept from frame to frame: an object
    // that did not move keeps its BVH (embree/scene.h, "Animation by parts").
    std::optional<embree::RayScene> rays;
    // The scene baked frame after frame, still objects kept where they are.
    scene::SceneBaker baker;
    std::vector<procedural::TerrainField> terrains;  // one per terrain pass, built once
    int rows_first = 0, rows_last = 1 << 30;  // set_rows
    // Reused from frame to frame (and region to region): its pages are touched once.
    VisibilityBuffer visibility;
    // --shadows map: each light's cascades, rendered again each frame into the same memory
    // where something in them moved (build_shadow_maps), by a rasterizer of their own (whose
    // buffers stay sized for the maps, not the frame).
    std::vector<shadow::ShadowMap> maps;
    pipeline::Rasterizer map_rasterizer;

    // Multisampled ray casting: each thread's layers of the tile in hand.
    tbb::enumerable_thread_specific<CoverageLayers> layers;
    // The frame's per-pass tile times; `clock` points at it only while a frame whose stats
    // were asked for renders, so without stats no pass reads the clock.
    TilePassClock pass_clock;
    TilePassClock* clock = nullptr;

    Impl(AnimatedScene& s, int w, int h, RendererKind r, ShadowMode sh, int n)
        : scene(s), width(w), height(h), renderer(r), shadows(sh), samples(n) {
        for (const PassSpec& p : scene.passes)
            if (p.kind == PassSpec::Kind::terrain) terrains.emplace_back(p.terrain);
    }

    // One frame's bracket: resets the stats, prepares what the frame's regions share, runs
    // body(state, stats), and times the whole.
    template <class Body>
    void frame(float time, FrameStats* stats, const Body& body);
    void prepare(float time, FrameState& frame, FrameStats& stats);
    // Renders `region` into `colour` (resized to region.width x region.height), shading only
    // the tiles that meet rows [rows_from, rows_to) of the region. With `rgba8` (the whole
    // frame only), the finished tiles are encoded there instead (render_srgb8), and `colour`
    // holds what the tiles needed of a float frame (nothing, for single-sampled raster tiles).
    struct Rgba8Target {
        uint8_t* bytes;
        std::atomic<uint64_t> non_finite{0};
    };
    void render_region(const FrameState& frame, const Region& region, std::vector<glm::vec4>& colour,
                       int rows_from, int rows_to, FrameStats& stats, Rgba8Target* rgba8 = nullptr);
    // Encodes rows [rect.y0, rect.y1) x [rect.x0, rect.x1) of a tile's colours (`colour` at
    // (rect.x0, rect.y0), rows `stride` apart) into `rgba8`.
    void encode_tile(const TileRect& rect, const glm::vec4* colour, size_t stride, Rgba8Target& rgba8) const;
    // render_srgb8's float frame where tiles need one (ray casting).
    std::vector<glm::vec4> float_frame;
    // The tile passes of one tile: shading, shadows, transparency, compute passes. `context`:
    // the rasterizer's, whose bins hold the transparent triangles (null under ray casting).
    void run_tile_passes(const FrameState& frame, const RegionPasses& passes, const VisibilityBuffer& visibility,
                         const Tile& tile, const pipeline::TileContext* context, std::atomic<uint64_t>& shadowed) const;
    // The pixels of `tile` that some light does not reach, shaded again without those lights.
    void shade_shadows(const FrameState& frame, const RegionPasses& passes, const VisibilityBuffer& visibility,
                       const Tile& tile, std::atomic<uint64_t>& shadowed) const;
    void shade_shadow_edges(const FrameState& frame, const RegionPasses& passes, const Tile& tile, size_t image_width,
                            const shadow::SurfacePoints& centre, std::span<const uint8_t> centre_lights,
                            std::span<const uint32_t> edges, std::atomic<uint64_t>& shadowed) const;
};

FrameRenderer::FrameRenderer(AnimatedScene& scene, int width, int height, RendererKind renderer,
                             ShadowMode shadows, int samples) {
    if (width <= 0 || height <= 0) throw std::invalid_argument("frame size must be positive");
    if (!pipeline::valid_sample_count(samples))
        throw std::invalid_argument("--samples: " + std::to_string(samples) + " is not a sample count (expected 1, 4, 8 or 16)");
    if (shadows != ShadowMode::none && scene.scene.lights.size() > 4)
        throw std::invalid_argument("--shadows: at most 4 lights cast shadows, the scene has " +
                                    std::to_string(scene.scene.lights.size()));
    if (shadows == ShadowMode::map)
        for (const scene::Light& light : scene.scene.lights) check_shadow_map_settings(light.shadow_map);
    impl_ = std::make_unique<Impl>(scene, width, height, renderer, shadows, samples);
    if (renderer == RendererKind::raytrace || shadows == ShadowMode::rays) impl_->device.emplace();
}

FrameRenderer::~FrameRenderer() = default;

void FrameRenderer::set_rows(int first, int last) {
    impl_->rows_first = first;
    impl_->rows_last = last;
}

template <class Body>
void FrameRenderer::Impl::frame(float time, FrameStats* stats, const Body& body) {
    FrameStats local;
    FrameStats& st = stats ? *stats : local;
    const auto t_frame = Clock::now();
    st = FrameStats{};
    clock = stats ? &pass_clock : nullptr;
    pass_clock.reset();
    FrameState state;
    prepare(time, state, st);
    body(state, st);
    st.tile_passes = pass_clock.times();
    st.total_ms = ms_since(t_frame);
}

Frame FrameRenderer::render(float time, FrameStats* stats) {
    Frame frame;
    render(time, frame, stats);
    return frame;
}

void FrameRenderer::render(float time, Frame& frame, FrameStats* stats) {
    Impl& im = *impl_;
    if (needs_bands(im.width, im.height))
        throw std::invalid_argument("a " + std::to_string(im.width) + "x" + std::to_string(im.height) +
                                    " frame is rendered in bands (render_bands)");
    // Every pixel is written below (render_region), so a reused frame needs no clearing.
    frame.width = im.width;
    frame.height = im.height;
    frame.pixels.resize(size_t(im.width) * size_t(im.height));
    im.frame(time, stats, [&](const FrameState& state, FrameStats& st) {
        im.render_region(state, Region{im.scene.scene.camera, im.width, im.height}, frame.pixels, im.rows_first,
                         im.rows_last, st);
    });
}

size_t FrameRenderer::render_srgb8(float time, std::vector<uint8_t>& rgba8, FrameStats* stats) {
    Impl& im = *impl_;
    if (needs_bands(im.width, im.height))
        throw std::invalid_argument("a " + std::to_string(im.width) + "x" + std::to_string(im.height) +
                                    " frame is rendered in bands (render_bands)");
    // Every pixel is written below, so a reused buffer needs no clearing.
    rgba8.resize(size_t(im.width) * size_t(im.height) * 4);
    Impl::Rgba8Target target{rgba8.data()};
    im.frame(time, stats, [&](const FrameState& state, FrameStats& st) {
        im.render_region(state, Region{im.scene.scene.camera, im.width, im.height}, im.float_frame, im.rows_first,
                         im.rows_last, st, &target);
    });
    return target.non_finite.load();
}

void FrameRenderer::Impl::encode_tile(const TileRect& rect, const glm::vec4* colour, size_t stride,
                                      Rgba8Target& rgba8) const {
    const size_t n = size_t(rect.width());
    for (int y = rect.y0; y < rect.y1; ++y) {
        const glm::vec4* row = colour + size_t(y - rect.y0) * stride;
        if (output::encode_srgb8(row, n, rgba8.bytes + (size_t(y) * size_t(width) + size_t(rect.x0)) * 4)) continue;
        uint64_t bad = 0;
        for (size_t i = 0; i < n; ++i)
            bad += !(std::isfinite(row[i].r) && std::isfinite(row[i].g) && std::isfinite(row[i].b) &&
                     std::isfinite(row[i].a));
        rgba8.non_finite += bad;
    }
}

void FrameRenderer::render_bands(float time, const BandLayout& layout, const BandFilter& mine,
                                 const BandSink& deliver, FrameStats* stats) {
    Impl& im = *impl_;
    if (layout.width != im.width || layout.height != im.height || layout.band_rows <= 0 ||
        layout.region_width <= 0 || layout.region_width > pipeline::kMaxViewport || layout.band_rows > pipeline::kMaxViewport)
        throw std::invalid_argument("render_bands: the band layout does not fit the renderer's " +
                                    std::to_string(im.width) + "x" + std::to_string(im.height) + " frame");
    im.frame(time, stats, [&](const FrameState& state, FrameStats& st) {
        const Camera& camera = im.scene.scene.camera;
        std::vector<glm::vec4> region;
        for (int b = 0; b < layout.bands(); ++b) {
            if (!mine(b)) continue;
            const auto [y0, y1] = layout.rows(b);
            const int rows = y1 - y0;
            Frame band(layout.width, rows);
            for (int x0 = 0; x0 < layout.width; x0 += layout.region_width) {
                const int w = std::min(layout.region_width, layout.width - x0);
                TraceScope trace("region", "region", x0, y0);
                im.render_region(state, Region{camera.region(im.width, im.height, x0, y0, w, rows), w, rows},
                                 region, 0, rows, st);
                for (int y = 0; y < rows; ++y)
                    std::copy_n(region.begin() + ptrdiff_t(y) * w, w,
                                band.pixels.begin() + ptrdiff_t(y) * layout.width + x0);
            }
            TraceScope trace("deliver band", "band", b);
            deliver(b, band);
        }
    });
}

void FrameRenderer::Impl::prepare(float time, FrameState& frame, FrameStats& stats) {
    scene::Scene& s = scene.scene;
    {
        TraceScope trace("animate");
        const auto t0 = Clock::now();
        scene.set_time(time, float(width) / float(height));
        stats.animate_ms = ms_since(t0);
    }
    {
        TraceScope trace("bake");
        const auto t0 = Clock::now();
        frame.baked = &baker.bake(s);
        stats.bake_ms = ms_since(t0);
    }
    stats.triangles = frame.baked->mesh.triangle_count();
    if (device) {
        TraceScope trace("bvh");
        const auto t0 = Clock::now();
        try {
            if (rays) rays->update(frame.baked->mesh, frame.baked->objects);
            else rays.emplace(*device, frame.baked->mesh, frame.baked->objects);
        } catch (...) {
            rays.reset();  // half updated: the next frame builds afresh
            throw;
        }
        frame.rays = &*rays;
        stats.bvh_objects = frame.baked->objects.size();
        stats.bvh_objects_built = rays->parts_built();
        stats.bvh_ms = ms_since(t0);
    }
    if (shadows != ShadowMode::none && !s.lights.empty()) {
        for (const scene::Light& l : s.lights) frame.light_targets.push_back(shadow_target(l));
        if (shadows == ShadowMode::rays) {
            frame.light_test = embree::shadow_ray_test(*frame.rays);
        } else {
            // Fitted to the whole frame's camera (regions and bands share the maps).
            TraceScope map_trace("shadow maps");
            const auto t0 = Clock::now();
            build_shadow_maps(map_rasterizer, frame.baked->mesh, s.lights, s.camera, maps);
            stats.shadow_maps_ms = ms_since(t0);
            for (const shadow::ShadowMap& map : maps) {
                stats.shadow_cascades += uint64_t(map.cascade_count());
                stats.shadow_cascades_drawn += uint64_t(map.cascades_rendered());
            }
            frame.light_test = shadow::shadow_map_test(maps);
        }
    }
    for (const PassSpec& p : scene.passes)
        if (p.kind == PassSpec::Kind::metaballs) {
            std::vector<march::Metaball> balls = march::orbiting_metaballs(p.count, time, p.ball_radius);
            for (march::Metaball& b : balls) b.centre = b.centre * p.orbit_scale + p.offset;
            frame.metaballs.emplace_back(balls, p.style);
        }
    bool any = false;
    for (const scene::Material& m : s.materials) any |= m.transparent() || m.masked();
    if (any) {
        const std::vector<uint32_t>& material = frame.baked->triangle_material;
        frame.transparent.resize(material.size());
        for (size_t t = 0; t < material.size(); ++t) {
            const scene::Material& m = s.materials[material[t]];
            frame.transparent[t] = m.masked() ? kAlphaTested : m.transparent() ? kBlended : kOpaque;
        }
    }
}

RegionPasses::RegionPasses(const AnimatedScene& scene, const FrameState& frame, const Region& region,
                           std::span<const procedural::TerrainField> terrains, const pipeline::ClipVertices* rasterized)
    : shading(*frame.baked, scene.scene,
              shade::RenderState{region.camera, region.width, region.height, scene.scene.lights, rasterized}),
      pixel_rays(region.camera.view_projection(), region.width, region.height),
      march_rays(region.camera, region.width, region.height) {
    const scene::Scene& s = scene.scene;
    const size_t light_count = frame.light_targets.size();
    all_lit = (1u << light_count) - 1u;
    if (light_count > 0) {
        TraceScope trace("shadow setup");
        subset_shading.resize(all_lit);
        tbb::parallel_for(uint32_t(0), all_lit, [&](uint32_t mask) {
            shade::RenderState dimmed = shading.state();
            for (size_t l = 0; l < light_count; ++l)
                if (!(mask & (1u << l))) dimmed.lights[l].Le = glm::vec3(0.0f);
            subset_shading[mask] = std::make_unique<shade::FrameShading>(*frame.baked, s, std::move(dimmed));
        });
    }
    size_t terrain_i = 0, metaball_i = 0;
    for (const PassSpec& p : scene.passes) {
        const march::SurfaceLook look{p.material, s.lights, {}};
        switch (p.kind) {
            case PassSpec::Kind::terrain: {
                auto pass = std::make_shared<march::SurfacePass<march::SlabSurface<procedural::TerrainField>>>(
                    march::terrain_surface(terrains[terrain_i++]), march_rays, p.settings, look, s.background);
                compute.push_back({TilePass::terrain, [pass](const Tile& t) { pass->run(t); }});
                break;
            }
            case PassSpec::Kind::metaballs: {
                auto pass = std::make_shared<march::SurfacePass<march::MetaballSurface>>(
                    march::MetaballSurface{frame.metaballs[metaball_i++]}, march_rays, p.settings, look, s.background);
                compute.push_back({TilePass::metaballs, [pass](const Tile& t) { pass->run(t); }});
                break;
            }
            case PassSpec::Kind::fog: {
                auto pass = std::make_shared<march::FogPass>(march_rays, p.fog);
                compute.push_back({TilePass::fog, [pass](const Tile& t) { pass->run(t); }});
                break;
            }
        }
    }
}

void FrameRenderer::Impl::shade_shadows(const FrameState& frame, const RegionPasses& passes,
                                        const VisibilityBuffer& visibility, const Tile& tile,
                                        std::atomic<uint64_t>& shadowed) const {
    TraceScope t("shadow test", "tile");
    // Per thread, kept from tile to tile.
    thread_local shadow::SurfacePoints points;
    thread_local std::vector<uint8_t> lit;
    thread_local std::vector<std::vector<shade::CoveredPixel>> groups;
    thread_local std::vector<glm::vec4> colours;
    thread_local std::vector<uint16_t> edge_scratch;
    thread_local std::vector<uint32_t> edges;
    const size_t w = size_t(visibility.width);
    shadow::gather_surface_points(tile, w, frame.baked->mesh, passes.pixel_rays, points, frame.light_targets);
    lit.assign(points.size(), 0);
    frame.light_test(points, frame.light_targets, lit);
    const uint32_t all_lit = passes.all_lit;
    // The lights reaching each point: those the test found, and those the surface turns away
    // from (their term is zero anyway). Through local pointers: a store through a byte
    // pointer may alias anything, so the vectors' own members would be read again per point.
    uint8_t* const lights_at = lit.data();
    const uint8_t* const facing = points.facing.data();
    const size_t count = points.size();
    for (size_t i = 0; i < count; ++i) lights_at[i] = uint8_t((lights_at[i] | ~facing[i]) & all_lit);
    edges.clear();
    if (samples > 1) {
        shadow::find_shadow_edges(tile, w, points, lit, samples, edge_scratch, edges);
        for (const uint32_t i : edges) lit[i] = uint8_t(all_lit);  // shaded from their samples below
    }
    groups.resize(std::max<size_t>(groups.size(), all_lit));
    for (uint32_t mask = 0; mask < all_lit; ++mask) groups[mask].clear();
    const uint32_t* const pixel = points.pixel.data();
    const uint32_t width = uint32_t(w);
    for (size_t i = 0; i < count; ++i) {
        const uint32_t mask = lights_at[i];
        if (mask == all_lit) continue;
        const int x = int(pixel[i] % width), y = int(pixel[i] / width);  // 32-bit divisions
        groups[mask].push_back({x, y, tile.triangle_at(x, y)});
    }
    for (uint32_t mask = 0; mask < all_lit; ++mask) {
        if (groups[mask].empty()) continue;
        colours.resize(groups[mask].size());
        passes.subset_shading[mask]->shade(groups[mask], colours);
        // An opaque surface covers its pixel, whatever alpha its material has.
        for (size_t i = 0; i < colours.size(); ++i)
            tile.colour_at(groups[mask][i].x, groups[mask][i].y) = glm::vec4(glm::vec3(colours[i]), 1.0f);
        shadowed += groups[mask].size();
    }
    if (!edges.empty()) shade_shadow_edges(frame, passes, tile, w, points, lit, edges, shadowed);
}

// The pixels find_shadow_edges chose (`edges`: indices of the points shade_shadows gathered,
// `centre`, whose lights are `centre_lights`): the lights tested again at each sample
// position on the surface, and the pixel's colour the average of its samples' colours, each
// shaded with the lights that reach that sample.
void FrameRenderer::Impl::shade_shadow_edges(const FrameState& frame, const RegionPasses& passes, const Tile& tile,
                                             size_t image_width, const shadow::SurfacePoints& centre,
                                             std::span<const uint8_t> centre_lights, std::span<const uint32_t> edges,
                                             std::atomic<uint64_t>& shadowed) const {
    TraceScope t("shadow edges", "tile");
    constexpr size_t kSets = 16;  // sets of lights: at most 4 lights cast shadows
    thread_local shadow::SurfacePoints at_sample;
    thread_local std::vector<uint8_t> lit;
    thread_local std::vector<uint32_t> pixels, slot_of, order;
    thread_local std::vector<uint8_t> count;  // [edge pixel][set of lights]: its samples so lit
    thread_local std::vector<uint8_t> seen;   // [edge pixel]: its samples placed on the surface
    thread_local std::vector<shade::CoveredPixel> to_shade;
    thread_local std::vector<glm::vec4> colours;
    thread_local std::vector<glm::vec3> sum;
    const size_t w = image_width;
    const TileRect& r = tile.rect;
    const uint32_t all_lit = passes.all_lit;
    const size_t n = size_t(samples);
    const auto local = [&](uint32_t p) {
        return (p / w - size_t(r.y0)) * size_t(r.width()) + (p % w - size_t(r.x0));
    };
    pixels.clear();
    slot_of.assign(size_t(r.width()) * size_t(r.height()), 0);
    for (const uint32_t i : edges) {
        slot_of[local(centre.pixel[i])] = uint32_t(pixels.size());
        pixels.push_back(centre.pixel[i]);
    }
    // Every sample starts with the centre's lights: a sample whose point cannot be placed (its
    // ray runs along the plane) keeps them.
    count.assign(pixels.size() * kSets, 0);
    seen.assign(pixels.size(), 0);
    const glm::vec2* positions = pipeline::sample_positions(samples);
    for (size_t s = 0; s < n; ++s) {
        shadow::gather_surface_points_at(tile, w, frame.baked->mesh, passes.pixel_rays, pixels, positions[s],
                                         at_sample, frame.light_targets);
        lit.assign(at_sample.size(), 0);
        frame.light_test(at_sample, frame.light_targets, lit);
        for (size_t i = 0; i < at_sample.size(); ++i) {
            const size_t k = slot_of[local(at_sample.pixel[i])];
            ++count[k * kSets + ((lit[i] | ~at_sample.facing[i]) & all_lit)];
            ++seen[k];
        }
    }
    for (size_t k = 0; k < pixels.size(); ++k) count[k * kSets + centre_lights[edges[k]]] += uint8_t(n - seen[k]);
    // Sums in a fixed order: the lit colour (shade_surfaces left it in the tile) times its
    // samples, then each other set of lights in increasing order.
    sum.resize(pixels.size());
    for (size_t k = 0; k < pixels.size(); ++k) {
        const int x = int(pixels[k] % w), y = int(pixels[k] / w);
        sum[k] = glm::vec3(tile.colour_at(x, y)) * float(count[k * kSets + all_lit]);
    }
    for (uint32_t set = 0; set < all_lit; ++set) {
        to_shade.clear();
        order.clear();
        for (size_t k = 0; k < pixels.size(); ++k)
            if (count[k * kSets + set] != 0) {
                const int x = int(pixels[k] % w), y = int(pixels[k] / w);
                to_shade.push_back({x, y, tile.triangle_at(x, y)});
                order.push_back(uint32_t(k));
            }
        if (to_shade.empty()) continue;
        colours.resize(to_shade.size());
        passes.subset_shading[set]->shade(to_shade, colours);
        for (size_t j = 0; j < order.size(); ++j)
            sum[order[j]] += glm::vec3(colours[j]) * float(count[order[j] * kSets + set]);
    }
    for (size_t k = 0; k < pixels.size(); ++k) {
        if (count[k * kSets + all_lit] == n) continue;  // every sample lit: the tile holds its colour
        tile.colour_at(int(pixels[k] % w), int(pixels[k] / w)) = glm::vec4(sum[k] / float(n), 1.0f);
        ++shadowed;
    }
}

void FrameRenderer::Impl::run_tile_passes(const FrameState& frame, const RegionPasses& passes,
                                          const VisibilityBuffer& visibility, const Tile& tile,
                                          const pipeline::TileContext* context,
                                          std::atomic<uint64_t>& shadowed) const {
    TraceScope trace("tile", "tile", tile.rect.x0, tile.rect.y0);
    {
        TraceScope t("shade", "tile");
        const TimedPass timed(clock, TilePass::shade);
        shade::shade_surfaces(passes.shading, tile);
    }
    {
        TraceScope t("background", "tile");
        const TimedPass timed(clock, TilePass::background);
        shade::shade_background(passes.shading, tile);
    }
    // Triangles outside the opaque pass, in front of its surface, in submission order: the
    // rasterizer replays its bins, rays collect them. Alpha-tested ones are decided first
    // (they are opaque where they survive: shadows and blending must see them). On a
    // multisampled layer their coverage is per sample, and pixels they cover only in part
    // are split by what their samples show (layer_split.h); the passes below then run on
    // each part.
    std::vector<shade::DepthFragment> blended;
    LayerSplit split;
    bool is_split = false;
    if (!frame.transparent.empty()) {
        TraceScope t("transparent", "tile");
        const TimedPass timed(clock, TilePass::transparent);
        std::vector<shade::DepthFragment> masked;
        const auto add = [&](uint32_t triangle, std::span<const pipeline::Fragment> f) {
            auto& to = frame.transparent[triangle] == kAlphaTested ? masked : blended;
            for (const pipeline::Fragment& frag : f) to.push_back({frag.x, frag.y, triangle, frag.depth, frag.mask});
        };
        if (context)
            context->for_each_transparent(add);
        else
            embree::for_each_transparent_hit(*frame.rays, passes.pixel_rays, frame.transparent, tile, add);
        std::vector<glm::vec4> masked_colours;
        if (!masked.empty()) shade::shade_alpha_tested(passes.shading, masked, masked_colours);
        is_split = split.split(tile, masked, masked_colours, blended);
        if (!masked.empty()) shade::apply_alpha_tested(masked, masked_colours, tile);
    }
    // The tile, or the parts a split made of it.
    const Tile& first = is_split ? split.main() : tile;
    const int parts = is_split ? 1 + split.extra_tiles() : 1;
    const auto part = [&](int k) -> const Tile& { return k == 0 ? first : split.extra(k - 1); };
    if (!passes.subset_shading.empty()) {
        const TimedPass timed(clock, TilePass::shadows);
        for (int k = 0; k < parts; ++k) shade_shadows(frame, passes, visibility, part(k), shadowed);
    }
    if (!blended.empty() || is_split) {
        // Blended over what is drawn so far, in submission order, where still in front (an
        // alpha-tested surface may have come nearer); on split pixels, as their groups decided.
        TraceScope t("blend", "tile");
        const TimedPass timed(clock, TilePass::blend);
        std::vector<shade::CoveredPixel> fragments;
        fragments.reserve(blended.size());
        for (const shade::DepthFragment& f : blended)
            if (f.depth < tile.depth_at(f.x, f.y)) fragments.push_back({f.x, f.y, f.triangle});
        if (is_split) {
            const std::span<const shade::CoveredPixel> decided = split.main_blended();
            fragments.insert(fragments.end(), decided.begin(), decided.end());
        }
        if (!fragments.empty()) shade::blend_fragments(passes.shading, fragments, first);
        for (int k = 1; k < parts; ++k)
            if (!split.extra_blended(k - 1).empty())
                shade::blend_fragments(passes.shading, split.extra_blended(k - 1), part(k));
    }
    for (const RegionPasses::ComputePass& pass : passes.compute) {
        TraceScope t("compute pass", "tile");
        const TimedPass timed(clock, pass.kind);
        for (int k = 0; k < parts; ++k) pass.run(part(k));
    }
    if (is_split) split.fold();
}

void FrameRenderer::Impl::render_region(const FrameState& frame, const Region& region,
                                        std::vector<glm::vec4>& colour, int rows_from, int rows_to,
                                        FrameStats& stats, Rgba8Target* rgba8) {
    const int w = region.width, h = region.height;
    const RegionPasses passes(scene, frame, region, terrains,
                              renderer == RendererKind::raster ? &rasterizer.clip_vertices() : nullptr);
    std::atomic<uint64_t> shadowed{0};
    const auto in_rows = [&](const TileRect& r) { return r.y1 > rows_from && r.y0 < rows_to; };

    if (renderer == RendererKind::raster) {
        TraceScope trace("raster");
        const auto t0 = Clock::now();
        pipeline::RasterOptions options;
        options.transparent = frame.transparent;
        options.samples = samples;
        // One sample: the passes read each tile's visibility in cache, and the frame's is not
        // written, unless the outlines read it across tiles afterwards.
        if (samples == 1 && !shade::any_outlined(scene.scene.materials)) {
            options.frame_visibility = false;
            options.tile_visibility_rows = true;
        }
        // 8-bit output: each tile is encoded from the rasterizer's colour tile (its clear
        // colour where the passes did not run; multisampled, once its layers are resolved), and
        // no float frame is written.
        const bool encode_tiles = rgba8 != nullptr;
        const pipeline::TilePass pass = [&](const pipeline::TileContext& c) {
            if (in_rows(c.rect)) {
                const TimedTile timed(clock);
                run_tile_passes(frame, passes, visibility, c, &c, shadowed);
            }
            if (encode_tiles && samples == 1) encode_tile(c.rect, c.colour, c.colour_stride, *rgba8);
        };
        if (encode_tiles && samples > 1)
            options.resolved_tile = [&](const TileRect& rect, const glm::vec4* resolved, size_t stride) {
                encode_tile(rect, resolved, stride, *rgba8);
            };
        pipeline::RasterStats raster;
        if (encode_tiles) options.tile_color = true;
        rasterizer.render(frame.baked->mesh, region.camera.view_projection(), pipeline::Viewport(w, h), options,
                          visibility, {&pass, 1}, encode_tiles ? nullptr : &colour, &raster);
        stats.raster += raster;
        stats.tiles_ms += raster.passes_ms;
        stats.visibility_ms += ms_since(t0) - raster.passes_ms;
    } else {
        {
            TraceScope trace("primary rays");
            const auto t0 = Clock::now();
            embree::cast_primary_rays(*frame.rays, region.camera.view_projection(), w, h, visibility,
                                      embree::RayPacket::x16, frame.transparent, samples);
            stats.visibility_ms += ms_since(t0);
        }
        TraceScope trace("tiles");
        const auto t0 = Clock::now();
        colour.resize(size_t(w) * size_t(h));
        // Multisampled, the rasterizer's tiles: the shadow edges a tile tests at its samples
        // include its border pixels (shadow_edges.h), so both renderers must cut the same tiles.
        const int tile_size = samples > 1 ? pipeline::RasterOptions{}.tile_size : 64;
        parallel_for_tiles(TileGrid(w, h, tile_size), [&](int, const TileRect& rect) {
            const Tile tile = frame_tile(visibility, colour.data(), rect);
            const TimedTile timed(in_rows(rect) ? clock : nullptr);
            if (in_rows(rect) && samples > 1) {
                // The passes once per layer of distinct surfaces, resolved (coverage_layers.h),
                // as the rasterizer runs them.
                CoverageLayers& l = layers.local();
                l.build(rect, samples, pipeline::sample_positions(samples), [&](int x, int y, int s, uint32_t& triangle, float& depth) {
                    triangle = visibility.sample_triangle[visibility.sample_index(x, y, s)];
                    depth = visibility.sample_depth[visibility.sample_index(x, y, s)];
                });
                l.set_sample_depths(&visibility.sample_depth[visibility.sample_index(rect.x0, rect.y0, 0)],
                                    size_t(visibility.width) * size_t(samples), size_t(samples), 1);
                for (int j = 0; j < l.layers(); ++j) {
                    run_tile_passes(frame, passes, visibility,
                                    l.layer(j, glm::vec4(0.0f), &tile.colour_at(rect.x0, rect.y0), tile.colour_stride),
                                    nullptr, shadowed);
                    l.accumulate();
                }
            } else if (in_rows(rect)) {
                run_tile_passes(frame, passes, visibility, tile, nullptr, shadowed);
            } else {
                // Unshaded, as the rasterizer leaves such tiles (its clear colour), whatever the
                // reused buffer held.
                for (int y = rect.y0; y < rect.y1; ++y)
                    std::fill_n(&tile.colour_at(rect.x0, y), rect.width(), glm::vec4(0.0f));
            }
            if (rgba8) encode_tile(rect, &tile.colour_at(rect.x0, rect.y0), tile.colour_stride, *rgba8);
        });
        stats.tiles_ms += ms_since(t0);
    }
    if (const shade::OutlinePass outlines(visibility, region.camera, frame.baked->triangle_material,
                                          scene.scene.materials);
        outlines.active()) {
        // Over the finished pixels (after fog): it reads the neighbours' depths, across tiles.
        TraceScope trace("outlines");
        const auto t0 = Clock::now();
        const int first = std::max(rows_from, 0), last = std::min(rows_to, h);
        if (first < last)
            // Bands of 16-32 rows: each band also reads the rows above and below it.
            tbb::parallel_for(tbb::blocked_range<int>(first, last, 32), [&](const tbb::blocked_range<int>& rows) {
                const TimedTile tile_time(clock);
                const TimedPass timed(clock, TilePass::outline);
                if (rgba8) outlines.run(rgba8->bytes, rows.begin(), rows.end());
                else outlines.run(colour, rows.begin(), rows.end());
            });
        stats.tiles_ms += ms_since(t0);
    }
    stats.shadowed_pixels += shadowed.load();
}

}  // namespace tessera::render
