// A rendered frame: linear-light float RGBA, rows top to bottom. What every renderer
// produces and every output encodes (output/frame_encoding.h).
#pragma once
#include <glm/glm.hpp>

#include <cstddef>
#include <vector>

namespace tessera {

struct Frame {
    int width = 0;
    int height = 0;
    std::vector<glm::vec4> pixels;  // width * height, row 0 at the top

    Frame() = default;
    Frame(int w, int h, glm::vec4 fill = glm::vec4(0.0f))
        : width(w), height(h), pixels(size_t(w) * size_t(h), fill) {}
    glm::vec4& at(int x, int y) { return pixels[size_t(y) * size_t(width) + size_t(x)]; }
    const glm::vec4& at(int x, int y) const { return pixels[size_t(y) * size_t(width) + size_t(x)]; }
};

}  // namespace tessera
