#include "raster/shade/scene_renderer.h"

#include "raster/shade/frame_shading.h"

namespace tessera {

Frame SceneRenderer::render(const Scene& scene, int width, int height, const SceneRenderOptions& options,
                            RasterStats* stats) {
    const Viewport viewport(width, height);
    const BakedScene baked = bake(scene);
    const FrameShading shading(baked, scene, RenderState{scene.camera, width, height, scene.lights});

    transparent_.assign(baked.triangle_material.size(), 0);
    bool any_transparent = false;
    for (size_t t = 0; t < baked.triangle_material.size(); ++t) {
        transparent_[t] = scene.materials[baked.triangle_material[t]].transparent();
        any_transparent |= transparent_[t] != 0;
    }
    RasterOptions raster;
    raster.cull = options.cull;
    raster.tile_size = options.tile_size;
    if (any_transparent) raster.transparent = transparent_;

    const TilePass shade_pass = [&](const TileContext& ctx) {
        TileTarget tile;
        tile.x0 = ctx.rect.x0;
        tile.y0 = ctx.rect.y0;
        tile.width = ctx.width();
        tile.height = ctx.height();
        tile.triangle = ctx.triangle;
        tile.triangle_stride = ctx.stride;
        tile.colour = ctx.color;
        tile.colour_stride = ctx.color_stride;
        shade_tile(shading, tile);
        if (!any_transparent) return;
        std::vector<CoveredPixel> pixels;
        ctx.for_each_transparent([&](uint32_t triangle, std::span<const Fragment> fragments) {
            pixels.clear();
            for (const Fragment& f : fragments) pixels.push_back({f.x, f.y, triangle});
            blend_fragments(shading, pixels, tile);
        });
    };
    rasterizer_.render(baked.mesh, scene.camera.view_projection(), viewport, raster, visibility_,
                       std::span<const TilePass>(&shade_pass, 1), &colour_, stats);
    Frame frame;
    frame.width = width;
    frame.height = height;
    frame.pixels.assign(colour_.begin(), colour_.end());
    return frame;
}

}  // namespace tessera
