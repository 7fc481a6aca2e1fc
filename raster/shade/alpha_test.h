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
#include <vector>

#include "raster/shade/frame_shading.h"

namespace tessera::shade {

// A fragment of a triangle outside the opaque pass: pixel (x, y), its window depth, and on a
// multisampled tile the samples it covers in front of the opaque surface (bit s: sample s;
// pipeline::Fragment::mask), 1 otherwise.
struct DepthFragment {
    int32_t x = 0;
    int32_t y = 0;
    uint32_t triangle = 0;
    float depth = 0.0f;
    uint16_t mask = 1;
};

// Resolves the masked fragments of one tile into its visibility (triangle ids and depth) and
// colour.
void resolve_alpha_tested(const FrameShading& shading, std::span<const DepthFragment> fragments, const Tile& tile);
// The two steps of resolve_alpha_tested: the fragments shaded once each at the pixel centre
// (alpha 1 where a fragment survives its cutoff, else 0; survives() reads it), and the
// surviving ones applied to the tile in order where nearer than what it shows.
void shade_alpha_tested(const FrameShading& shading, std::span<const DepthFragment> fragments,
                        std::vector<glm::vec4>& colours);
inline bool survives(const glm::vec4& colour) { return !(colour.a < 0.5f); }
void apply_alpha_tested(std::span<const DepthFragment> fragments, std::span<const glm::vec4> colours, const Tile& tile);

}  // namespace tessera::shade
