#include "procedural/erosion.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <stdexcept>

#include "procedural/denormals.h"

namespace tessera::procedural {

void erode_thermal(Grid& heights, const ThermalErosion& p) {
    const int w = heights.width, h = heights.height;
    check_grid_size(w, h, "heightfield");
    if (!(p.rate > 0.0f && p.rate <= 0.5f)) throw std::invalid_argument("erosion rate must be in (0, 0.5]");
    if (std::isnan(p.talus)) throw std::invalid_argument("erosion talus must be a number");
    if (p.iterations < 0) throw std::invalid_argument("erosion iterations must be >= 0");
    const float talus = p.talus > 0.0f ? p.talus : 4.0f / float(w);
    const bool wrap = p.boundary == Boundary::periodic;
    // Neighbour index along one axis; a clamped edge's outside neighbour is the cell itself,
    // whose drop is 0, so nothing flows across the edge.
    auto at = [wrap](int i, int n) { return i < 0 ? (wrap ? n - 1 : 0) : (i >= n ? (wrap ? 0 : n - 1) : i); };

    Grid factor(w, h), next(w, h);
    for (int it = 0; it < p.iterations; ++it) {
        // Pass 1: factor = c (d_max - T) / d_total over neighbours lower by more than T.
        tbb::parallel_for(tbb::blocked_range<int>(0, h, 16), [&](const tbb::blocked_range<int>& rows) {
            const FlushDenormals flush;
            for (int y = rows.begin(); y < rows.end(); ++y) {
                const float* up = heights.row(at(y - 1, h));
                const float* row = heights.row(y);
                const float* down = heights.row(at(y + 1, h));
                float* f = factor.row(y);
                for (int x = 0; x < w; ++x) {
                    const float c = row[x];
                    const float d[4] = {c - row[at(x - 1, w)], c - row[at(x + 1, w)], c - up[x], c - down[x]};
                    float d_max = 0.0f, d_total = 0.0f;
                    for (float di : d)
                        if (di > talus) {
                            d_max = std::fmax(d_max, di);
                            d_total += di;
                        }
                    f[x] = d_total > 0.0f ? p.rate * (d_max - talus) / d_total : 0.0f;
                }
            }
        });
        // Pass 2: new = old - sum of own outflows + inflows from higher neighbours, each flow
        // being factor(sender) * drop; a cell's outflows sum to c (d_max - T).
        tbb::parallel_for(tbb::blocked_range<int>(0, h, 16), [&](const tbb::blocked_range<int>& rows) {
            const FlushDenormals flush;
            for (int y = rows.begin(); y < rows.end(); ++y) {
                const int yu = at(y - 1, h), yd = at(y + 1, h);
                const float* row = heights.row(y);
                float* out = next.row(y);
                for (int x = 0; x < w; ++x) {
                    const int xl = at(x - 1, w), xr = at(x + 1, w);
                    const int nx[4] = {xl, xr, x, x}, ny[4] = {y, y, yu, yd};
                    const float c = row[x], own = factor.at(x, y);
                    float change = 0.0f;
                    for (int i = 0; i < 4; ++i) {
                        const float n = heights.at(nx[i], ny[i]);
                        const float drop_out = c - n, drop_in = n - c;
                        if (drop_out > talus) change -= own * drop_out;
                        if (drop_in > talus) change += factor.at(nx[i], ny[i]) * drop_in;
                    }
                    out[x] = c + change;
                }
            }
        });
        std::swap(heights.values, next.values);
    }
}

}  // namespace tessera::procedural
