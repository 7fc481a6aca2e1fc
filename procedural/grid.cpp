#include "procedural/grid.h"

#include <stdexcept>
#include <string>

namespace tessera::procedural {

void check_grid_size(int width, int height, const char* what) {
    if (width <= 0 || height <= 0 || width > kMaxGridSide || height > kMaxGridSide)
        throw std::invalid_argument(std::string(what) + " size " + std::to_string(width) + "x" +
                                    std::to_string(height) + " is out of range (1.." +
                                    std::to_string(kMaxGridSide) + " per side)");
}

Grid::Grid(int w, int h, float fill) : width(w), height(h) {
    check_grid_size(w, h, "grid");
    values.assign(size_t(w) * size_t(h), fill);
}

}  // namespace tessera::procedural
