// A 2-D array of floats, row-major (x fastest), the one data type every generator reads and
// writes: reaction-diffusion concentrations, heights, feed/kill maps, normal-map channels.
// Plain data so that callers (the renderer, the command, tests) can hand it around freely.
#pragma once
#include <cstddef>
#include <vector>

namespace tessera::procedural {

// Largest width or height a generator accepts. 65536^2 floats is already 16 GiB, so the real
// limit for a run is memory (the command checks that); this bound keeps every index product
// far from overflow.
inline constexpr int kMaxGridSide = 1 << 16;

// Throws std::invalid_argument naming `what` unless 0 < width, height <= kMaxGridSide.
void check_grid_size(int width, int height, const char* what);

struct Grid {
    int width = 0;
    int height = 0;
    std::vector<float> values;  // width * height, row y starts at y * width

    Grid() = default;
    // A width x height grid filled with `fill`; checks the size (check_grid_size).
    Grid(int width, int height, float fill = 0.0f);

    size_t size() const { return values.size(); }
    float* row(int y) { return values.data() + size_t(y) * size_t(width); }
    const float* row(int y) const { return values.data() + size_t(y) * size_t(width); }
    float& at(int x, int y) { return row(y)[x]; }
    float at(int x, int y) const { return row(y)[x]; }
};

// What to do at the grid's edges when a stencil reaches past them.
enum class Boundary {
    periodic,  // wrap around: the result tiles seamlessly (Ready and jsexp wrap too)
    clamped,   // repeat the edge cell (zero-flux / Neumann boundary for diffusion)
};

}  // namespace tessera::procedural
