// Alpha-tested surfaces (scene::Material::masked, glTF 2.0's alphaMode MASK: foliage, fences,
// decals cut out of a texture). Whether such a triangle covers a pixel depends on a texture
// lookup, so neither the rasterizer's depth test nor Embree's closest hit can decide it alone:
// both renderers leave masked triangles out of their opaque visibility, as they do the blended
// ones, and hand over their fragments in front of the opaque surface (with window depth, in
// submission order). This pass decides them, the same way for both: a fragment whose alpha
// reaches its material's cutoff and lies nearer than what the pixel shows becomes the pixel's
// opaque surface (triangle id, depth and colour), so the nearest surviving fragment wins.
// Shadows and blending, which run after it, see masked surfaces like any opaque one.
#pragma once
#include <cstdint>
#include <span>

#include "raster/shade/frame_shading.h"

namespace tessera::shade {

// A fragment of a triangle outside the opaque pass: pixel (x, y) and its window depth.
struct DepthFragment {
    int32_t x = 0;
    int32_t y = 0;
    uint32_t triangle = 0;
    float depth = 0.0f;
};

// Resolves the masked fragments of one tile into its visibility (triangle ids and depth) and
// colour.
void resolve_alpha_tested(const FrameShading& shading, std::span<const DepthFragment> fragments, const Tile& tile);

}  // namespace tessera::shade
