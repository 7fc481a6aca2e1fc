#include "procedural/normal_map.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace tessera::procedural {

NormalMap normal_map(const Grid& heights, float strength, Boundary boundary) {
    const int w = heights.width, h = heights.height;
    check_grid_size(w, h, "height map");
    if (!std::isfinite(strength)) throw std::invalid_argument("normal-map strength must be a finite number");
    NormalMap out{w, h, std::vector<float>(size_t(w) * size_t(h) * 3)};
    const bool wrap = boundary == Boundary::periodic;
    auto neighbour = [wrap](int i, int n) {  // index i in [-1, n] mapped into [0, n)
        if (i < 0) return wrap ? n - 1 : 0;
        if (i >= n) return wrap ? 0 : n - 1;
        return i;
    };
    tbb::parallel_for(tbb::blocked_range<int>(0, h, 8), [&](const tbb::blocked_range<int>& rows) {
        for (int y = rows.begin(); y < rows.end(); ++y) {
            const float* up = heights.row(neighbour(y - 1, h));
            const float* down = heights.row(neighbour(y + 1, h));
            const float* row = heights.row(y);
            float* n = out.xyz.data() + size_t(y) * size_t(w) * 3;
            for (int x = 0; x < w; ++x) {
                const float dhdx = 0.5f * (row[neighbour(x + 1, w)] - row[neighbour(x - 1, w)]);
                const float dhdrow = 0.5f * (down[x] - up[x]);
                // v points up the image: dh/dv = -dh/drow, so n.y = -s dh/dv = s dh/drow.
                const float nx = -strength * dhdx, ny = strength * dhdrow;
                const float squared = nx * nx + ny * ny + 1.0f;
                if (std::isfinite(squared)) {
                    const float inv = 1.0f / std::sqrt(squared);
                    n[3 * x + 0] = nx * inv;
                    n[3 * x + 1] = ny * inv;
                    n[3 * x + 2] = inv;
                } else {
                    // A strength so large that the squares overflow float (1e38: the normals lie
                    // nearly flat): in double, scaled by the largest component first, the
                    // direction stays exact (the products of two floats are exact in double).
                    const double dx = -double(strength) * dhdx, dy = double(strength) * dhdrow;
                    const double largest = std::max({std::fabs(dx), std::fabs(dy), 1.0});
                    const double sx = dx / largest, sy = dy / largest, sz = 1.0 / largest;
                    const double inv = 1.0 / std::sqrt(sx * sx + sy * sy + sz * sz);
                    n[3 * x + 0] = float(sx * inv);
                    n[3 * x + 1] = float(sy * inv);
                    n[3 * x + 2] = float(sz * inv);
                }
            }
        }
    });
    return out;
}

std::vector<uint8_t> encode_normals_rgb8(const NormalMap& normals) {
    std::vector<uint8_t> rgb(normals.xyz.size());
    for (size_t i = 0; i < rgb.size(); ++i) {
        const float v = std::fmin(std::fmax(normals.xyz[i] * 0.5f + 0.5f, 0.0f), 1.0f);
        rgb[i] = uint8_t(std::lround(v * 255.0f));
    }
    return rgb;
}

}  // namespace tessera::procedural
