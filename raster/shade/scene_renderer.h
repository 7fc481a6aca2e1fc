// One frame of a Scene through the tile rasterizer, shaded: the glue between the scene model,
// the raster core and shading.
//
//   bake (world-space mesh + material ids) -> FrameShading (clip corners, Gouraud colours)
//   -> Rasterizer::render with one tile pass that, per tile while it is hot in cache,
//      shades the visible pixels (opaque pass) and then blends the tile's transparent
//      triangles' fragments in submission order (for_each_transparent)
//   -> Frame (linear RGBA).
//
// Animation is the caller's: call scene.animate(t) before render().
#pragma once
#include "raster/output/frame.h"
#include "raster/rasterizer.h"
#include "raster/scene/scene.h"

namespace tessera {

struct SceneRenderOptions {
    CullMode cull = CullMode::none;  // the seed's flag needs both sides
    int tile_size = 64;
};

class SceneRenderer {
public:
    // Throws std::invalid_argument for a bad size or scene (see bake, Viewport).
    Frame render(const Scene& scene, int width, int height, const SceneRenderOptions& options = {},
                 RasterStats* stats = nullptr);

private:
    Rasterizer rasterizer_;  // keeps its scratch memory between frames
    VisibilityBuffer visibility_;
    std::vector<glm::vec4> colour_;
    std::vector<uint8_t> transparent_;
};

}  // namespace tessera
