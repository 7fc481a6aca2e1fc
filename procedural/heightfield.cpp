#include "procedural/heightfield.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "procedural/fractal_batch.h"

namespace tessera::procedural {

namespace {
void check(const HeightfieldParams& p) {
    if (p.fractal.octaves < 1 || p.fractal.octaves > 24)
        throw std::invalid_argument("heightfield octaves must be in 1..24");
    if (!(p.fractal.gain > 0.0f && p.fractal.gain < 1.0f) ||
        !(p.fractal.lacunarity >= 1.0f && p.fractal.lacunarity <= 16.0f))
        throw std::invalid_argument("heightfield gain must be in (0, 1) and lacunarity in [1, 16]");
    if (p.cells < 1 || p.cells > 1 << 20) throw std::invalid_argument("heightfield cells must be >= 1");
    if (p.tileable && p.relief != Relief::dunes && p.fractal.lacunarity != std::floor(p.fractal.lacunarity))
        throw std::invalid_argument("a tileable heightfield needs a whole-number lacunarity");
    if (!std::isfinite(p.warp) || !(p.dunes.wavelength > 0.0f) || !(p.dunes.ripple_wavelength > 0.0f))
        throw std::invalid_argument("heightfield warp must be finite and dune wavelengths positive");
}

// One row of relief at lattice rows v, columns xs (ys: v repeated), through the batch forms,
// vectorised over the row. The lattice and the dune waves are either both open or both
// repeating over the map.
template <class Lattice>
void relief_row(const HeightfieldParams& p, Lattice lattice, const DuneWaves<Lattice>& waves,
                int width, const float* xs, const float* ys, float* h) {
    switch (p.relief) {
        case Relief::fbm: fbm_batch(p.fractal, lattice, width, xs, ys, h); break;
        case Relief::ridged: ridged_batch(p.fractal, 1.0f, lattice, width, xs, ys, h); return;
        case Relief::warped: domain_warp_batch(p.fractal, p.warp, lattice, width, xs, ys, h); break;
        case Relief::dunes: dunes_batch(p.dunes, waves, width, xs, ys, h); return;
    }
    for (int x = 0; x < width; ++x) h[x] = 0.5f * h[x] + 0.5f;  // fbm and warped: [-1, 1] to [0, 1]
}
}  // namespace

Grid generate_heightfield(int width, int height, const HeightfieldParams& p) {
    check_grid_size(width, height, "heightfield");
    check(p);
    Grid out(width, height);
    // Lattice units per texel: the same along both axes (square features); the height holds a
    // whole number of cells so that a tileable map also wraps vertically.
    const int cells_y = std::max(1, int(std::lround(double(p.cells) * height / width)));
    const float sx = float(p.cells) / float(width), sy = float(cells_y) / float(height);
    // A tileable map repeats every cells x cells_y lattice units: the map's own extent.
    const glm::ivec2 period(p.cells, cells_y);
    const DuneWaves<TorusLattice> tiled_waves = dune_waves(p.dunes, period);
    const DuneWaves<OpenLattice> open_waves = dune_waves(p.dunes);
    tbb::parallel_for(tbb::blocked_range<int>(0, height, 4), [&](const tbb::blocked_range<int>& rows) {
        std::vector<float> xs(width), ys(width);
        for (int x = 0; x < width; ++x) xs[x] = float(x) * sx;
        for (int y = rows.begin(); y < rows.end(); ++y) {
            std::fill(ys.begin(), ys.end(), float(y) * sy);
            if (p.tileable)
                relief_row(p, TorusLattice{period}, tiled_waves, width, xs.data(), ys.data(), out.row(y));
            else
                relief_row(p, OpenLattice{}, open_waves, width, xs.data(), ys.data(), out.row(y));
        }
    });
    return out;
}

void normalize_heights(Grid& g) {
    using Range = std::pair<float, float>;
    const Range r = tbb::parallel_reduce(
        tbb::blocked_range<size_t>(0, g.size(), 1 << 16), Range{INFINITY, -INFINITY},
        [&](const tbb::blocked_range<size_t>& b, Range acc) {
            for (size_t i = b.begin(); i < b.end(); ++i)
                acc = {std::min(acc.first, g.values[i]), std::max(acc.second, g.values[i])};
            return acc;
        },
        [](Range a, Range b) { return Range{std::min(a.first, b.first), std::max(a.second, b.second)}; });
    const float span = r.second - r.first;
    const float scale = span > 0.0f ? 1.0f / span : 0.0f;
    for (float& v : g.values) v = (v - r.first) * scale;
}

}  // namespace tessera::procedural
