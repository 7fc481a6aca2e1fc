// The pixels a compute pass works on: one rectangle (a tile) of the frame's buffers, as the
// tile stage hands it over after visibility. Depth is window depth (z_ndc * 0.5 + 0.5, 1
// where nothing was drawn); colour is linear RGBA; the optional triangle ids let a pass that
// covers a rasterized pixel mark it as no longer showing that triangle.
#pragma once
#include <glm/glm.hpp>

#include <cstddef>
#include <cstdint>

namespace tessera::march {

struct PassTarget {
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;  // frame pixels [x0, x1) x [y0, y1)
    float* depth = nullptr;              // pixel (x0, y0); rows `depth_stride` elements apart
    size_t depth_stride = 0;
    glm::vec4* colour = nullptr;  // pixel (x0, y0); rows `colour_stride` elements apart
    size_t colour_stride = 0;
    uint32_t* triangle = nullptr;  // optional, rows `depth_stride` apart like depth

    float& depth_at(int x, int y) const { return depth[size_t(y - y0) * depth_stride + size_t(x - x0)]; }
    glm::vec4& colour_at(int x, int y) const {
        return colour[size_t(y - y0) * colour_stride + size_t(x - x0)];
    }
};

}  // namespace tessera::march
