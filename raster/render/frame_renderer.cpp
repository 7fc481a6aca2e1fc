#include "raster/render/frame_renderer.h"

#include <tbb/blocked_range2d.h>
#include <tbb/parallel_for.h>

#include <chrono>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "raster/embree/device.h"
#include "raster/embree/pixel_rays.h"
#include "raster/embree/ray_cast.h"
#include "raster/embree/scene.h"
#include "raster/embree/shadow_rays.h"
#include "raster/march/fog_pass.h"
#include "raster/march/march_surface.h"
#include "raster/march/metaball_orbits.h"
#include "raster/march/procedural_surfaces.h"
#include "raster/march/surface_pass.h"
#include "raster/shade/frame_shading.h"
#include "raster/shadow/light_mask.h"
#include "raster/shadow/shadow_map.h"
#include "raster/shadow/surface_points.h"
#include "raster/trace.h"

namespace tessera {

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

using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

// Shadow rays need a point to aim at: a directional light (w = 0) becomes a point far along
// its direction, far beyond any scene here, so the rays are parallel to within 1e-4 rad.
constexpr float kDistantLight = 1.0e4f;

glm::vec3 shadow_target(const Light& light) {
    const glm::vec3 p(light.position);
    return light.position.w == 0.0f ? glm::normalize(p) * kDistantLight : p;
}

// The pixels of one tile, wherever they live (the rasterizer's tile view or a full frame).
struct TileView {
    int x0, y0, x1, y1;
    uint32_t* triangle;
    float* depth;
    size_t stride;
    glm::vec4* colour;
    size_t colour_stride;
    const TileContext* context;  // raster renderer only (transparent triangles)
};

}  // namespace

struct FrameRenderer::Impl {
    AnimatedScene& scene;
    int width, height;
    RendererKind renderer;
    ShadowMode shadows;
    Rasterizer rasterizer;
    std::optional<rt::RayDevice> device;
    std::vector<procedural::TerrainField> terrains;  // one per terrain pass, built once
    int rows_first = 0, rows_last = 1 << 30;  // set_rows

    Impl(AnimatedScene& s, int w, int h, RendererKind r, ShadowMode sh)
        : scene(s), width(w), height(h), renderer(r), shadows(sh) {
        for (const PassSpec& p : scene.spec.passes)
            if (p.kind == PassSpec::Kind::terrain) terrains.emplace_back(p.terrain);
    }

    Frame render(float time, FrameStats& stats);
};

FrameRenderer::FrameRenderer(AnimatedScene& scene, int width, int height, RendererKind renderer,
                             ShadowMode shadows) {
    if (width <= 0 || height <= 0) throw std::invalid_argument("frame size must be positive");
    if (shadows != ShadowMode::none && scene.scene.lights.size() > 4)
        throw std::invalid_argument("--shadows: at most 4 lights cast shadows, the scene has " +
                                    std::to_string(scene.scene.lights.size()));
    impl_ = std::make_unique<Impl>(scene, width, height, renderer, shadows);
    if (renderer == RendererKind::raytrace || shadows == ShadowMode::rays) impl_->device.emplace();
}

FrameRenderer::~FrameRenderer() = default;

void FrameRenderer::set_rows(int first, int last) {
    impl_->rows_first = first;
    impl_->rows_last = last;
}

Frame FrameRenderer::render(float time, FrameStats* stats) {
    FrameStats local;
    Frame frame = impl_->render(time, stats ? *stats : local);
    return frame;
}

Frame FrameRenderer::Impl::render(float time, FrameStats& stats) {
    const auto t_frame = Clock::now();
    stats = FrameStats{};
    Scene& s = scene.scene;
    {
        TraceScope trace("animate");
        const auto t0 = Clock::now();
        scene.set_time(time, float(width) / float(height));
        stats.animate_ms = ms_since(t0);
    }
    BakedScene baked;
    {
        TraceScope trace("bake");
        const auto t0 = Clock::now();
        baked = bake(s);
        rt::reserve_ray_padding(baked.mesh);
        stats.bake_ms = ms_since(t0);
    }
    stats.triangles = baked.mesh.triangle_count();
    const glm::mat4 view_projection = s.camera.view_projection();

    std::optional<rt::RayScene> rays;
    if (device) {
        TraceScope trace("bvh");
        const auto t0 = Clock::now();
        rays.emplace(*device, baked.mesh, rt::BvhUpdate::rebuild);
        stats.bvh_ms = ms_since(t0);
    }

    const RenderState state{s.camera, width, height, s.lights};
    const FrameShading shading(baked, s, state);

    // Shadows: one shading per subset of lit lights (bit l set: light l reaches the point).
    const size_t light_count = s.lights.size();
    const uint32_t all_lit = (1u << light_count) - 1u;
    std::vector<std::unique_ptr<FrameShading>> subset_shading;
    std::vector<glm::vec3> light_targets;
    std::vector<shadow::ShadowMap> maps;
    shadow::LightTest light_test;
    if (shadows != ShadowMode::none && light_count > 0) {
        TraceScope trace("shadow setup");
        subset_shading.resize(all_lit);
        tbb::parallel_for(uint32_t(0), all_lit, [&](uint32_t mask) {
            RenderState dimmed = state;
            for (size_t l = 0; l < light_count; ++l)
                if (!(mask & (1u << l))) dimmed.lights[l].Le = glm::vec3(0.0f);
            subset_shading[mask] = std::make_unique<FrameShading>(baked, s, std::move(dimmed));
        });
        for (const Light& l : s.lights) light_targets.push_back(shadow_target(l));
        if (shadows == ShadowMode::rays) {
            light_test = rt::shadow_ray_test(*rays);
        } else {
            TraceScope map_trace("shadow maps");
            maps.reserve(light_count);
            for (const glm::vec3& light : light_targets) maps.emplace_back(rasterizer, baked.mesh, light);
            light_test = shadow::shadow_map_test(maps);
        }
    }
    const rt::PixelRays pixel_rays(view_projection, width, height);
    std::atomic<uint64_t> shadowed{0};

    // The scene's compute passes for this frame.
    const march::RayGenerator march_rays(s.camera, width, height);
    std::vector<march::MetaballField> metaballs;
    for (const PassSpec& p : scene.spec.passes)
        if (p.kind == PassSpec::Kind::metaballs) {
            std::vector<march::Metaball> balls = march::orbiting_metaballs(p.count, time, p.ball_radius);
            for (march::Metaball& b : balls) b.centre = b.centre * p.orbit_scale + p.offset;
            metaballs.emplace_back(balls, p.style);
        }
    std::vector<std::function<void(const march::PassTarget&)>> compute_passes;
    {
        size_t terrain_i = 0, metaball_i = 0;
        for (const PassSpec& p : scene.spec.passes) {
            const march::SurfaceLook look{p.material, s.lights, {}};
            switch (p.kind) {
                case PassSpec::Kind::terrain: {
                    auto pass = std::make_shared<march::SurfacePass<march::SlabSurface<procedural::TerrainField>>>(
                        march::terrain_surface(terrains[terrain_i++]), march_rays, p.settings, look, s.background);
                    compute_passes.push_back([pass](const march::PassTarget& t) { pass->run(t); });
                    break;
                }
                case PassSpec::Kind::metaballs: {
                    auto pass = std::make_shared<march::SurfacePass<march::MetaballSurface>>(
                        march::MetaballSurface{metaballs[metaball_i++]}, march_rays, p.settings, look, s.background);
                    compute_passes.push_back([pass](const march::PassTarget& t) { pass->run(t); });
                    break;
                }
                case PassSpec::Kind::fog: {
                    auto pass = std::make_shared<march::FogPass>(march_rays, p.fog);
                    compute_passes.push_back([pass](const march::PassTarget& t) { pass->run(t); });
                    break;
                }
            }
        }
    }

    VisibilityBuffer visibility;
    const auto tile_work = [&](const TileView& v) {
        if (v.y1 <= rows_first || v.y0 >= rows_last) return;
        TraceScope trace("tile", "tile", v.x0, v.y0);
        const TileTarget target{v.x0, v.y0, v.x1 - v.x0, v.y1 - v.y0, v.triangle, v.stride, v.colour, v.colour_stride};
        {
            TraceScope t("shade", "tile");
            shade_tile(shading, target);
        }
        if (!subset_shading.empty()) {
            TraceScope t("shadow test", "tile");
            shadow::SurfacePoints points;
            shadow::gather_surface_points(visibility, baked.mesh, pixel_rays, rt::ImageTile{v.x0, v.y0, v.x1, v.y1},
                                          points);
            std::vector<uint8_t> lit(points.size(), 0), facing(points.size(), 0);
            shadow::facing_lights(points, light_targets, facing);
            light_test(points, light_targets, lit);
            std::vector<std::vector<CoveredPixel>> groups(all_lit);
            for (size_t i = 0; i < points.size(); ++i) {
                const uint32_t mask = (lit[i] | ~facing[i]) & all_lit;
                if (mask == all_lit) continue;
                const uint32_t p = points.pixel[i];
                const int x = int(p % uint32_t(width)), y = int(p / uint32_t(width));
                groups[mask].push_back({x, y, visibility.triangle[p]});
            }
            std::vector<glm::vec4> colours;
            for (uint32_t mask = 0; mask < all_lit; ++mask) {
                if (groups[mask].empty()) continue;
                colours.resize(groups[mask].size());
                subset_shading[mask]->shade(groups[mask], colours);
                for (size_t i = 0; i < colours.size(); ++i) {
                    const CoveredPixel& c = groups[mask][i];
                    v.colour[size_t(c.y - v.y0) * v.colour_stride + size_t(c.x - v.x0)] = colours[i];
                }
                shadowed += groups[mask].size();
            }
        }
        if (v.context) {
            // Transparent triangles, blended in submission order over what is drawn so far.
            std::vector<CoveredPixel> fragments;
            v.context->for_each_transparent([&](uint32_t triangle, std::span<const Fragment> f) {
                for (const Fragment& frag : f) fragments.push_back({frag.x, frag.y, triangle});
            });
            if (!fragments.empty()) blend_fragments(shading, fragments, target);
        }
        for (const auto& pass : compute_passes) {
            TraceScope t("compute pass", "tile");
            pass(march::PassTarget{v.x0, v.y0, v.x1, v.y1, v.depth, v.stride, v.colour, v.colour_stride, v.triangle});
        }
    };

    Frame frame(width, height);
    if (renderer == RendererKind::raster) {
        TraceScope trace("raster");
        const auto t0 = Clock::now();
        std::vector<uint8_t> transparent;
        bool any_transparent = false;
        for (const Material& m : s.materials) any_transparent |= m.transparent();
        if (any_transparent) {
            transparent.resize(baked.mesh.triangle_count());
            for (size_t t = 0; t < transparent.size(); ++t) transparent[t] = shading.transparent(uint32_t(t)) ? 1 : 0;
        }
        RasterOptions options;
        options.transparent = transparent;
        const TilePass pass = [&](const TileContext& c) {
            tile_work(TileView{c.rect.x0, c.rect.y0, c.rect.x1, c.rect.y1, c.triangle, c.depth, c.stride, c.color,
                               c.color_stride, &c});
        };
        rasterizer.render(baked.mesh, view_projection, Viewport(width, height), options, visibility, {&pass, 1},
                          &frame.pixels, &stats.raster);
        stats.tiles_ms = stats.raster.passes_ms;
        stats.visibility_ms = ms_since(t0) - stats.tiles_ms;
    } else {
        {
            TraceScope trace("primary rays");
            const auto t0 = Clock::now();
            rt::cast_primary_rays(*rays, view_projection, width, height, visibility);
            stats.visibility_ms = ms_since(t0);
        }
        TraceScope trace("tiles");
        const auto t0 = Clock::now();
        constexpr int kTile = 64;
        const int tiles_x = (width + kTile - 1) / kTile, tiles_y = (height + kTile - 1) / kTile;
        tbb::parallel_for(tbb::blocked_range2d<int>(0, tiles_y, 1, 0, tiles_x, 1),
                          [&](const tbb::blocked_range2d<int>& r) {
            for (int ty = r.rows().begin(); ty != r.rows().end(); ++ty)
                for (int tx = r.cols().begin(); tx != r.cols().end(); ++tx) {
                    const int x0 = tx * kTile, y0 = ty * kTile;
                    const size_t at = size_t(y0) * size_t(width) + size_t(x0);
                    tile_work(TileView{x0, y0, std::min(width, x0 + kTile), std::min(height, y0 + kTile),
                                       visibility.triangle.data() + at, visibility.depth.data() + at, size_t(width),
                                       frame.pixels.data() + at, size_t(width), nullptr});
                }
        }, tbb::simple_partitioner());
        stats.tiles_ms = ms_since(t0);
    }
    stats.shadowed_pixels = shadowed.load();
    stats.total_ms = ms_since(t_frame);
    return frame;
}

}  // namespace tessera
