// The pixels a compute pass works on: one rectangle (a tile) of the frame's depth and colour
// buffers, as the tile stage hands it over after visibility. Depth is window depth
// (z_ndc * 0.5 + 0.5, 1 where nothing was drawn); colour is linear RGBA.
#pragma once
#include <glm/glm.hpp>

namespace tessera::march {

struct PassTarget {
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;  // frame pixels [x0, x1) x [y0, y1)
    float* depth = nullptr;              // pixel (x0, y0); rows `stride` elements apart
    glm::vec4* colour = nullptr;
    int stride = 0;

    float& depth_at(int x, int y) const { return depth[(y - y0) * stride + (x - x0)]; }
    glm::vec4& colour_at(int x, int y) const { return colour[(y - y0) * stride + (x - x0)]; }
};

}  // namespace tessera::march
