#include "procedural/reaction_diffusion.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "procedural/denormals.h"

namespace tessera::procedural {

float laplacian_spectral_radius(float anisotropy) {
    // lambda(cx, cy) = -1 + 0.4 (1 + a) cx + 0.4 (1 - a) cy + 0.2 cx cy with cx = cos(wx),
    // cy = cos(wy) in [-1, 1]: bilinear, so its minimum sits at a corner of the square.
    return std::max(1.6f, 1.2f + 0.8f * std::abs(anisotropy));
}

float max_stable_dt(const GrayScott& p) {
    return 2.0f / (std::max(p.diffusion_a, p.diffusion_b) * laplacian_spectral_radius(p.anisotropy));
}

void validate(const GrayScott& p, int width, int height) {
    check_grid_size(width, height, "reaction-diffusion grid");
    auto in = [](float v, float lo, float hi) { return v >= lo && v <= hi; };  // false for NaN
    if (!in(p.feed, 0.0f, 1.0f) || !in(p.kill, 0.0f, 1.0f))
        throw std::invalid_argument("feed and kill rates must be numbers in [0, 1] (got f=" +
                                    std::to_string(p.feed) + ", k=" + std::to_string(p.kill) + ")");
    if (!in(p.diffusion_a, 0.0f, 1e3f) || !in(p.diffusion_b, 0.0f, 1e3f))
        throw std::invalid_argument("diffusion rates must be numbers in [0, 1000]");
    if (!in(p.anisotropy, -1.0f, 1.0f))
        throw std::invalid_argument("anisotropy must be a number in [-1, 1]");
    if (!(p.dt > 0.0f) || !std::isfinite(p.dt))
        throw std::invalid_argument("time step dt must be a positive number");
    if (p.dt > max_stable_dt(p))
        throw std::invalid_argument(
            "time step dt=" + std::to_string(p.dt) + " is unstable: explicit Euler diffusion "
            "needs D*dt*" + std::to_string(laplacian_spectral_radius(p.anisotropy)) +
            " <= 2, so dt <= " + std::to_string(max_stable_dt(p)) + " for these rates");
    for (const Grid* map : {p.feed_map, p.kill_map}) {
        if (!map) continue;
        if (map->width != width || map->height != height)
            throw std::invalid_argument("feed/kill map is " + std::to_string(map->width) + "x" +
                                        std::to_string(map->height) + ", the grid " +
                                        std::to_string(width) + "x" + std::to_string(height));
        for (float v : map->values)
            if (!in(v, 0.0f, 1.0f))
                throw std::invalid_argument("feed/kill map values must be numbers in [0, 1]");
    }
}

namespace {

struct Coefficients {
    float edge_x, edge_y, corner;  // Laplacian weights (centre -1)
    float da, db, dt, feed, kill;
};

// One row's inputs (rows above, at and below, for A and B) and outputs.
struct Row {
    const float* au;
    const float* ac;
    const float* ad;
    const float* bu;
    const float* bc;
    const float* bd;
    const float* feed;  // per-cell maps, or null
    const float* kill;
    float* na;
    float* nb;
};

// Cells [begin, end) of a row, whose left and right neighbours are x - left_shift and
// x + right_shift. One straight loop over __restrict parameters (GCC honours restrict on
// parameters, not on locals) with the coefficients by value, so GCC vectorises it: SIMD over x,
// checked with -fopt-info-vec.
template <bool Maps>
void update_span(const float* __restrict au, const float* __restrict ac, const float* __restrict ad,
                 const float* __restrict bu, const float* __restrict bc, const float* __restrict bd,
                 const float* __restrict fm, const float* __restrict km, float* __restrict na,
                 float* __restrict nb, const Coefficients c, int begin, int end, int left_shift,
                 int right_shift) {
    for (int x = begin; x < end; ++x) {
        const int xl = x - left_shift, xr = x + right_shift;
        const float la = c.edge_x * (ac[xl] + ac[xr]) + c.edge_y * (au[x] + ad[x]) +
                         c.corner * ((au[xl] + au[xr]) + (ad[xl] + ad[xr])) - ac[x];
        const float lb = c.edge_x * (bc[xl] + bc[xr]) + c.edge_y * (bu[x] + bd[x]) +
                         c.corner * ((bu[xl] + bu[xr]) + (bd[xl] + bd[xr])) - bc[x];
        const float f = Maps ? fm[x] : c.feed;
        const float k = Maps ? km[x] : c.kill;
        const float a = ac[x], b = bc[x];
        const float abb = a * b * b;
        na[x] = a + (c.da * la - abb + f * (1.0f - a)) * c.dt;
        nb[x] = b + (c.db * lb + abb - (k + f) * b) * c.dt;
    }
}

template <bool Maps>
void update_span(const Row& r, const Coefficients& c, int begin, int end, int left_shift,
                 int right_shift) {
    update_span<Maps>(r.au, r.ac, r.ad, r.bu, r.bc, r.bd, r.feed, r.kill, r.na, r.nb, c, begin,
                      end, left_shift, right_shift);
}

template <bool Maps>
void update_row(const Row& r, const Coefficients& c, int width, Boundary boundary) {
    if (width == 1) {  // both neighbours are the cell itself, for either boundary rule
        update_span<Maps>(r, c, 0, 1, 0, 0);
        return;
    }
    const bool periodic = boundary == Boundary::periodic;
    // Left edge: neighbour at width-1 (wrap) or 0 (repeat the edge cell).
    update_span<Maps>(r, c, 0, 1, periodic ? 1 - width : 0, 1);
    update_span<Maps>(r, c, 1, width - 1, 1, 1);
    update_span<Maps>(r, c, width - 1, width, 1, periodic ? 1 - width : 0);
}

}  // namespace

ReactionDiffusion::ReactionDiffusion(const GrayScott& params, RdState initial)
    : params_(params), current_(std::move(initial)) {
    const int w = current_.a.width, h = current_.a.height;
    if (current_.b.width != w || current_.b.height != h)
        throw std::invalid_argument("reaction-diffusion: A and B grids differ in size");
    validate(params_, w, h);
    next_ = current_;
}

void ReactionDiffusion::step(int steps) {
    const int w = current_.a.width, h = current_.a.height;
    const float anis = params_.anisotropy;
    const Coefficients c{0.2f * (1.0f + anis), 0.2f * (1.0f - anis), 0.05f, params_.diffusion_a,
                         params_.diffusion_b, params_.dt, params_.feed, params_.kill};
    const bool maps = params_.feed_map || params_.kill_map;
    // Maps given singly use the scalar rate for the other one (a constant-filled grid).
    Grid feed_fill, kill_fill;
    if (maps && !params_.feed_map) feed_fill = Grid(w, h, params_.feed);
    if (maps && !params_.kill_map) kill_fill = Grid(w, h, params_.kill);
    const Grid* feed = params_.feed_map ? params_.feed_map : &feed_fill;
    const Grid* kill = params_.kill_map ? params_.kill_map : &kill_fill;
    const bool periodic = params_.boundary == Boundary::periodic;
    // About 64k cells per task: well above oneTBB's 100k-cycle guidance at ~2 cycles a cell.
    const int grain = std::max(1, 65536 / w);

    for (int s = 0; s < steps; ++s) {
        tbb::parallel_for(tbb::blocked_range<int>(0, h, grain), [&](const tbb::blocked_range<int>& rows) {
            const FlushDenormals flush;
            for (int y = rows.begin(); y < rows.end(); ++y) {
                const int up = y > 0 ? y - 1 : (periodic ? h - 1 : 0);
                const int down = y + 1 < h ? y + 1 : (periodic ? 0 : h - 1);
                const Row r{current_.a.row(up), current_.a.row(y), current_.a.row(down),
                            current_.b.row(up), current_.b.row(y), current_.b.row(down),
                            maps ? feed->row(y) : nullptr, maps ? kill->row(y) : nullptr,
                            next_.a.row(y), next_.b.row(y)};
                if (maps)
                    update_row<true>(r, c, w, params_.boundary);
                else
                    update_row<false>(r, c, w, params_.boundary);
            }
        });
        std::swap(current_, next_);
        ++steps_done_;
    }
}

}  // namespace tessera::procedural
