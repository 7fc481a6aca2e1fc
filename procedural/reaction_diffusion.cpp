#include "procedural/reaction_diffusion.h"

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

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

// The sum of each cell's left and right neighbours in one row, under the grid's x rule:
// pair[x] = row[x - 1] + row[x + 1], wrapped (periodic) or the edge cell repeated (clamped) at
// the ends. A cell's Laplacian reads this sum for its own row (the edge term) and for the rows
// above and below (the corner terms), so computing it once per row and step instead of three
// times gives the same float additions on the same operands: the same bits as update_span.
// pair[i] = centre[i - 1] + centre[i + 1] for i in [0, count), pair 64-byte aligned.
void aligned_pair_sums(const float* __restrict centre, float* __restrict pair, int count) {
    for (int i = 0; i < count; ++i) pair[i] = centre[i - 1] + centre[i + 1];
}

void pair_sums(const float* __restrict row, float* __restrict pair, int width, bool periodic) {
    if (width == 1) {
        pair[0] = row[0] + row[0];
        return;
    }
    pair[0] = row[periodic ? width - 1 : 0] + row[1];
    // The interior in two loops: cells up to pair's next 64-byte boundary, then the rest with
    // every store aligned. One loop from x = 1 stored every vector across two cache lines (a
    // ring slot starts on a line when the width is a multiple of 16); aligned stores take
    // BM_RdStep/256/1/8 from ~0.53 to ~0.47 ms.
    int x = 1;
    for (; x < width - 1 && (reinterpret_cast<uintptr_t>(pair + x) & 63) != 0; ++x) pair[x] = row[x - 1] + row[x + 1];
    aligned_pair_sums(row + x, static_cast<float*>(__builtin_assume_aligned(pair + x, 64)), width - 1 - x);
    pair[width - 1] = row[width - 2] + row[periodic ? 0 : width - 1];
}

// update_span over a whole row from the neighbour pair sums of the rows above, at and below
// (pair_sums), in update_span's order of operations: la = edge_x * (left + right) +
// edge_y * (up + down) + corner * ((up-left + up-right) + (down-left + down-right)) - centre.
// Every load is aligned with the cell (no shifted loads), and 4 of update_span's ~37 float
// operations per cell are gone. kUnitRates: Da = 1 and dt = 1, whose products are skipped
// (x * 1 is x exactly in IEEE arithmetic, signed zeros, infinities and NaNs included).
template <bool Maps, bool kUnitRates>
void update_row_from_pairs(const float* __restrict au, const float* __restrict ac, const float* __restrict ad,
                           const float* __restrict pau, const float* __restrict pac, const float* __restrict pad,
                           const float* __restrict bu, const float* __restrict bc, const float* __restrict bd,
                           const float* __restrict pbu, const float* __restrict pbc, const float* __restrict pbd,
                           const float* __restrict fm, const float* __restrict km, float* __restrict na,
                           float* __restrict nb, const Coefficients c, int width) {
    for (int x = 0; x < width; ++x) {
        const float la = c.edge_x * pac[x] + c.edge_y * (au[x] + ad[x]) + c.corner * (pau[x] + pad[x]) - ac[x];
        const float lb = c.edge_x * pbc[x] + c.edge_y * (bu[x] + bd[x]) + c.corner * (pbu[x] + pbd[x]) - bc[x];
        const float f = Maps ? fm[x] : c.feed;
        const float k = Maps ? km[x] : c.kill;
        const float a = ac[x], b = bc[x];
        const float abb = a * b * b;
        if constexpr (kUnitRates) {
            na[x] = a + (la - abb + f * (1.0f - a));
            nb[x] = b + (c.db * lb + abb - (k + f) * b);
        } else {
            na[x] = a + (c.da * la - abb + f * (1.0f - a)) * c.dt;
            nb[x] = b + (c.db * lb + abb - (k + f) * b) * c.dt;
        }
    }
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

namespace {

// Temporal blocking: a pass advances kFusedSteps steps on one tile at a time. The tile and a
// halo of kFusedSteps cells on each side are copied into per-thread scratch small enough for
// L2; each step there shrinks the valid region by one cell per side, and after the last one
// the tile itself is valid and is written out. DRAM traffic per cell-step falls from ~16-24
// bytes to about (halo growth) * 8 / k + 8 / k, so grids larger than the caches are no longer
// held to the memory roofline; the price is recomputing the halo (a few percent for 512-wide
// tiles). Every cell is still computed by the same update_span arithmetic from the same
// neighbour values, so results do not depend on the tiling or the thread count (tested bit for
// bit against single steps).
constexpr int kFusedSteps = 4;

struct Scratch {
    std::vector<float> a[2], b[2], feed, kill;
};

// Copies `count` cells of a row starting at (possibly out-of-range) column `start`, wrapping
// around a row of `width` cells, in as few contiguous runs as possible.
void copy_wrapped(const float* row, int width, int start, int count, float* out) {
    int g = ((start % width) + width) % width;
    while (count > 0) {
        const int run = std::min(count, width - g);
        std::copy_n(row + g, run, out);
        out += run;
        count -= run;
        g = 0;
    }
}

}  // namespace

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
    auto update = [&](const Row& r) {
        if (maps)
            update_row<true>(r, c, w, params_.boundary);
        else
            update_row<false>(r, c, w, params_.boundary);
    };

    // One step straight from the global grids to the global grids, row by row through the
    // rows' neighbour pair sums (pair_sums), kept in a ring of three per species: row y reads
    // those of y - 1, y and y + 1, and computes only y + 1's.
    const bool unit_rates = c.da == 1.0f && c.dt == 1.0f;
    tbb::enumerable_thread_specific<std::vector<float>> pair_rings;
    // The same rows to the same thread step after step (as far as oneTBB can): a grid this
    // size lives in the cores' L2 caches, and rows that changed thread from one step to the
    // next were fetched from the other core's cache each time.
    tbb::affinity_partitioner affinity;
    auto single_pass = [&] {
        // About 16k cells per task: above oneTBB's 100k-cycle guidance at ~2 cycles a cell, and
        // a cached grid still splits across threads.
        const int grain = std::max(1, 16384 / w);
        tbb::parallel_for(tbb::blocked_range<int>(0, h, grain), [&](const tbb::blocked_range<int>& rows) {
            const FlushDenormals flush;
            std::vector<float>& ring = pair_rings.local();
            ring.resize(6 * size_t(w));
            auto pa = [&](int slot) { return ring.data() + size_t(slot) * size_t(w); };
            auto pb = [&](int slot) { return ring.data() + size_t(3 + slot) * size_t(w); };
            auto up_of = [&](int y) { return y > 0 ? y - 1 : (periodic ? h - 1 : 0); };
            auto down_of = [&](int y) { return y + 1 < h ? y + 1 : (periodic ? 0 : h - 1); };
            const int first = rows.begin();
            pair_sums(current_.a.row(up_of(first)), pa(0), w, periodic);
            pair_sums(current_.b.row(up_of(first)), pb(0), w, periodic);
            pair_sums(current_.a.row(first), pa(1), w, periodic);
            pair_sums(current_.b.row(first), pb(1), w, periodic);
            for (int y = first; y < rows.end(); ++y) {
                const int up = up_of(y), down = down_of(y);
                const int su = (y - first) % 3, sc = (y - first + 1) % 3, sd = (y - first + 2) % 3;
                pair_sums(current_.a.row(down), pa(sd), w, periodic);
                pair_sums(current_.b.row(down), pb(sd), w, periodic);
                const float* fm = maps ? feed->row(y) : nullptr;
                const float* km = maps ? kill->row(y) : nullptr;
                const auto run = [&](auto kernel) {
                    kernel(current_.a.row(up), current_.a.row(y), current_.a.row(down), pa(su), pa(sc), pa(sd),
                           current_.b.row(up), current_.b.row(y), current_.b.row(down), pb(su), pb(sc), pb(sd),
                           fm, km, next_.a.row(y), next_.b.row(y), c, w);
                };
                if (maps)
                    unit_rates ? run(update_row_from_pairs<true, true>) : run(update_row_from_pairs<true, false>);
                else
                    unit_rates ? run(update_row_from_pairs<false, true>) : run(update_row_from_pairs<false, false>);
            }
        }, affinity);
    };

    // k steps tile by tile through scratch (see kFusedSteps). Tiles are 512 columns wide (the
    // full row when the grid is narrower than 768) and as tall as ~48k cells of tile + halo
    // allow per scratch buffer (4 buffers: ~768 KiB, L2), at least 8 rows and at most h/8 so
    // that small grids still split across threads. The layout depends only on the grid size.
    tbb::enumerable_thread_specific<Scratch> scratch;
    auto blocked_pass = [&](int k) {
        const int tile_w = w < 768 ? w : 512;
        const bool full_rows = tile_w == w;
        const int halo_w = full_rows ? w : tile_w + 2 * k;
        const int band = std::clamp(49152 / halo_w - 2 * k, 8, std::max(8, h / 8));
        const int bands = (h + band - 1) / band, columns = (w + tile_w - 1) / tile_w;
        tbb::parallel_for(tbb::blocked_range<int>(0, bands * columns, 1), [&](const tbb::blocked_range<int>& range) {
            const FlushDenormals flush;
            Scratch& s = scratch.local();
            for (int index = range.begin(); index < range.end(); ++index) {
                const int y0 = (index / columns) * band, y1 = std::min(h, y0 + band);
                const int x0 = (index % columns) * tile_w, x1 = std::min(w, x0 + tile_w);
                const int lo = periodic ? y0 - k : std::max(0, y0 - k);
                const int hi = periodic ? y1 + k : std::min(h, y1 + k);
                const int left = full_rows ? 0 : (periodic ? x0 - k : std::max(0, x0 - k));
                const int right = full_rows ? w : (periodic ? x1 + k : std::min(w, x1 + k));
                const int rows = hi - lo, cols = right - left;
                auto global_row = [&](int r) { return ((lo + r) % h + h) % h; };
                for (int i = 0; i < 2; ++i) {
                    s.a[i].resize(size_t(rows) * cols);
                    s.b[i].resize(size_t(rows) * cols);
                }
                auto local = [&](std::vector<float>& v, int r) { return v.data() + size_t(r) * cols; };
                const bool local_maps = maps && !full_rows;
                if (local_maps) {
                    s.feed.resize(size_t(rows) * cols);
                    s.kill.resize(size_t(rows) * cols);
                }
                for (int r = 0; r < rows; ++r) {
                    const int g = global_row(r);
                    copy_wrapped(current_.a.row(g), w, left, cols, local(s.a[0], r));
                    copy_wrapped(current_.b.row(g), w, left, cols, local(s.b[0], r));
                    if (local_maps) {
                        copy_wrapped(feed->row(g), w, left, cols, local(s.feed, r));
                        copy_wrapped(kill->row(g), w, left, cols, local(s.kill, r));
                    }
                }
                // A clamped grid edge inside the scratch stays valid: its outside neighbour is
                // itself. A full-row tile applies the grid's own x rule (update_row).
                const bool top = !periodic && lo == 0, bottom = !periodic && hi == h;
                const bool left_edge = !periodic && left == 0, right_edge = !periodic && right == w;
                int row_lo = 0, row_hi = rows, col_lo = 0, col_hi = cols;
                for (int j = 0; j < k; ++j) {
                    const int src = j & 1, dst = src ^ 1;
                    const int out_lo = top ? 0 : row_lo + 1, out_hi = bottom ? rows : row_hi - 1;
                    const int c_lo = full_rows || left_edge ? 0 : col_lo + 1;
                    const int c_hi = full_rows || right_edge ? cols : col_hi - 1;
                    for (int r = out_lo; r < out_hi; ++r) {
                        const int up = r > 0 ? r - 1 : r, down = r + 1 < rows ? r + 1 : r;
                        const int g = global_row(r);
                        const Row row{local(s.a[src], up), local(s.a[src], r), local(s.a[src], down),
                                      local(s.b[src], up), local(s.b[src], r), local(s.b[src], down),
                                      !maps ? nullptr : (local_maps ? local(s.feed, r) : feed->row(g)),
                                      !maps ? nullptr : (local_maps ? local(s.kill, r) : kill->row(g)),
                                      local(s.a[dst], r), local(s.b[dst], r)};
                        if (full_rows) {
                            update(row);
                            continue;
                        }
                        // Columns [c_lo, c_hi); a clamped grid edge repeats its own cell.
                        int begin = c_lo, end = c_hi;
                        const int right_shift_last = right_edge && end == cols ? 0 : 1;
                        if (left_edge && begin == 0) {
                            maps ? update_span<true>(row, c, 0, 1, 0, 1) : update_span<false>(row, c, 0, 1, 0, 1);
                            begin = 1;
                        }
                        if (right_shift_last == 0) --end;
                        maps ? update_span<true>(row, c, begin, end, 1, 1) : update_span<false>(row, c, begin, end, 1, 1);
                        if (right_shift_last == 0)
                            maps ? update_span<true>(row, c, end, end + 1, 1, 0) : update_span<false>(row, c, end, end + 1, 1, 0);
                    }
                    row_lo = out_lo;
                    row_hi = out_hi;
                    col_lo = c_lo;
                    col_hi = c_hi;
                }
                for (int y = y0; y < y1; ++y) {
                    std::copy_n(local(s.a[k & 1], y - lo) + (x0 - left), x1 - x0, next_.a.row(y) + x0);
                    std::copy_n(local(s.b[k & 1], y - lo) + (x0 - left), x1 - x0, next_.b.row(y) + x0);
                }
            }
        });
    };

    // A grid whose four arrays (A and B, this step and the next) fit one core's L2 (256^2) is
    // not held to the memory roofline: temporal blocking would only add its halo and copies
    // (about 1.3-1.8x the CPU of single steps at 256^2, bench_procedural BM_RdStep).
    const bool in_cache = size_t(w) * size_t(h) <= size_t(1) << 16;
    while (steps > 0) {
        const int k = in_cache ? 1 : std::min(steps, kFusedSteps);
        if (k == 1)
            single_pass();
        else
            blocked_pass(k);
        std::swap(current_, next_);
        steps_done_ += k;
        steps -= k;
    }
}

}  // namespace tessera::procedural
