// The plain Gray-Scott step: one thread, one cell at a time, modulo indexing for the
// neighbours, no SIMD-friendly structure. It is the baseline bench_procedural measures the
// library's step against, and the reference tests/procedural_rd_test.cpp compares it with.
#pragma once
#include "procedural/reaction_diffusion.h"

namespace tessera::procedural::reference {

// One explicit Euler step of `in` into `out` (same size), exactly the formula of
// reaction_diffusion.h, read literally.
inline void gray_scott_step(const GrayScott& p, const RdState& in, RdState& out) {
    const int w = in.a.width, h = in.a.height;
    const bool wrap = p.boundary == Boundary::periodic;
    auto at = [&](const Grid& g, int x, int y) {
        if (wrap) {
            x = (x + w) % w;
            y = (y + h) % h;
        } else {
            x = x < 0 ? 0 : (x >= w ? w - 1 : x);
            y = y < 0 ? 0 : (y >= h ? h - 1 : y);
        }
        return g.at(x, y);
    };
    const float ex = 0.2f * (1 + p.anisotropy), ey = 0.2f * (1 - p.anisotropy), corner = 0.05f;
    auto laplacian = [&](const Grid& g, int x, int y) {
        return ex * (at(g, x - 1, y) + at(g, x + 1, y)) + ey * (at(g, x, y - 1) + at(g, x, y + 1)) +
               corner * (at(g, x - 1, y - 1) + at(g, x + 1, y - 1) + at(g, x - 1, y + 1) + at(g, x + 1, y + 1)) -
               g.at(x, y);
    };
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const float f = p.feed_map ? p.feed_map->at(x, y) : p.feed;
            const float k = p.kill_map ? p.kill_map->at(x, y) : p.kill;
            const float a = in.a.at(x, y), b = in.b.at(x, y);
            out.a.at(x, y) = a + (p.diffusion_a * laplacian(in.a, x, y) - a * b * b + f * (1 - a)) * p.dt;
            out.b.at(x, y) = b + (p.diffusion_b * laplacian(in.b, x, y) + a * b * b - (k + f) * b) * p.dt;
        }
}

}  // namespace tessera::procedural::reference
