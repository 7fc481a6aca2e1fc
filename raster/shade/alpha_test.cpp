#include "raster/shade/alpha_test.h"

#include <vector>

namespace tessera::shade {

void shade_alpha_tested(const FrameShading& shading, std::span<const DepthFragment> fragments,
                        std::vector<glm::vec4>& colours) {
    std::vector<CoveredPixel> pixels(fragments.size());
    for (size_t i = 0; i < fragments.size(); ++i) pixels[i] = {fragments[i].x, fragments[i].y, fragments[i].triangle};
    colours.resize(fragments.size());
    shading.shade(pixels, colours);  // alpha is 1 where the fragment survives the cutoff, else 0
}

void apply_alpha_tested(std::span<const DepthFragment> fragments, std::span<const glm::vec4> colours, const Tile& tile) {
    for (size_t i = 0; i < fragments.size(); ++i) {
        const DepthFragment& f = fragments[i];
        if (!survives(colours[i])) continue;
        if (!(f.depth < tile.depth_at(f.x, f.y))) continue;  // LESS, as the opaque pass tests
        tile.depth_at(f.x, f.y) = f.depth;
        tile.triangle_at(f.x, f.y) = f.triangle;
        tile.colour_at(f.x, f.y) = glm::vec4(glm::vec3(colours[i]), 1.0f);
    }
}

void resolve_alpha_tested(const FrameShading& shading, std::span<const DepthFragment> fragments, const Tile& tile) {
    std::vector<glm::vec4> colours;
    shade_alpha_tested(shading, fragments, colours);
    apply_alpha_tested(fragments, colours, tile);
}

}  // namespace tessera::shade
