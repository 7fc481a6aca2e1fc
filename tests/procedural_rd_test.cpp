// Reaction-diffusion: the parallel SIMD step agrees with the plain scalar reference, is
// bit-identical for 1 and 2 threads, keeps concentrations finite and in [0, 1], grows the
// pattern class its preset names, flushes denormals, and rejects bad parameters.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstring>
#include <vector>

#include "procedural/reaction_diffusion_reference.h"
#include "procedural/rd_color.h"
#include "procedural/rd_initial.h"
#include "procedural/rd_presets.h"
#include "procedural/reaction_diffusion.h"

namespace tp = tessera::procedural;

namespace {

tp::GrayScott preset(const char* name) {
    const tp::RdPreset* p = tp::find_rd_preset(name);
    EXPECT_NE(p, nullptr) << name;
    tp::GrayScott g;
    g.feed = p->feed;
    g.kill = p->kill;
    return g;
}

tp::RdState run(const tp::GrayScott& g, tp::RdState initial, int steps) {
    tp::ReactionDiffusion rd(g, std::move(initial));
    rd.step(steps);
    return rd.state();
}

// Connected regions where B > threshold (4-neighbours, wrapping around the edges).
struct Blobs {
    int count = 0;
    int largest = 0;
};
Blobs blobs(const tp::Grid& b, float threshold) {
    const int w = b.width, h = b.height;
    std::vector<char> seen(b.size(), 0);
    std::vector<int> stack;
    Blobs r;
    for (int start = 0; start < w * h; ++start) {
        if (seen[start] || b.values[start] <= threshold) continue;
        int size = 0;
        seen[start] = 1;
        stack.push_back(start);
        while (!stack.empty()) {
            const int i = stack.back();
            stack.pop_back();
            ++size;
            const int x = i % w, y = i / w;
            for (int n : {y * w + (x + 1) % w, y * w + (x + w - 1) % w, ((y + 1) % h) * w + x,
                          ((y + h - 1) % h) * w + x})
                if (!seen[n] && b.values[n] > threshold) {
                    seen[n] = 1;
                    stack.push_back(n);
                }
        }
        ++r.count;
        r.largest = std::max(r.largest, size);
    }
    return r;
}

}  // namespace

TEST(ProceduralRd, MatchesScalarReference) {
    for (tp::Boundary boundary : {tp::Boundary::periodic, tp::Boundary::clamped}) {
        // Odd sizes and a 1-wide grid exercise the edge cells and the vector loop's remainder;
        // 1100 columns take the x-tiled fused path (512-wide tiles, a partial last one).
        for (auto [w, h] : {std::pair{37, 23}, std::pair{1, 9}, std::pair{64, 2}, std::pair{1100, 13}}) {
            tp::GrayScott g = preset("spots");
            g.boundary = boundary;
            g.anisotropy = 0.3f;
            tp::Grid feed(w, h), kill(w, h);
            for (int y = 0; y < h; ++y)
                for (int x = 0; x < w; ++x) {
                    feed.at(x, y) = 0.02f + 0.03f * float(x) / float(w);
                    kill.at(x, y) = 0.06f + 0.005f * float(y) / float(h);
                }
            for (bool maps : {false, true}) {
                g.feed_map = maps ? &feed : nullptr;
                g.kill_map = maps ? &kill : nullptr;
                tp::RdState ref = tp::rd_initial_noise(w, h, 5, 3.0f);
                tp::ReactionDiffusion rd(g, ref);
                tp::RdState scratch = ref;
                for (int s = 0; s < 30; ++s) {
                    tp::reference::gray_scott_step(g, ref, scratch);
                    std::swap(ref, scratch);
                }
                rd.step(30);
                float worst = 0;
                for (size_t i = 0; i < ref.a.size(); ++i)
                    worst = std::max({worst, std::abs(ref.a.values[i] - rd.state().a.values[i]),
                                      std::abs(ref.b.values[i] - rd.state().b.values[i])});
                EXPECT_LT(worst, 1e-5f) << w << "x" << h << " maps " << maps << " periodic "
                                        << (boundary == tp::Boundary::periodic);
            }
        }
    }
}

TEST(ProceduralRd, BitIdenticalForOneAndTwoThreads) {
    const tp::GrayScott g = preset("stripes");
    std::vector<tp::RdState> results;
    for (int threads : {1, 2}) {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
        results.push_back(run(g, tp::rd_initial_spots(160, 96, 3), 400));
    }
    ASSERT_EQ(results[0].a.size(), results[1].a.size());
    EXPECT_EQ(0, std::memcmp(results[0].a.values.data(), results[1].a.values.data(), results[0].a.size() * 4));
    EXPECT_EQ(0, std::memcmp(results[0].b.values.data(), results[1].b.values.data(), results[0].b.size() * 4));
}

// step(n) fuses steps band by band (temporal blocking) on grids larger than 256^2 cells;
// single steps do not, and go row by row through the rows' neighbour pair sums. Both compute
// every cell with the same float operations on the same neighbours, so they agree bit for bit.
// 300x260 and 1100x64 take the fused path (full-row tiles, 512-wide x tiles); a dt below 1
// takes the single steps' kernel that multiplies by Da and dt.
TEST(ProceduralRd, FusedStepsEqualSingleSteps) {
    for (tp::Boundary boundary : {tp::Boundary::periodic, tp::Boundary::clamped}) {
        for (auto [w, h] : {std::pair{200, 150}, std::pair{1030, 40}, std::pair{300, 260}, std::pair{1100, 64}}) {
            tp::GrayScott g = preset("coral");
            g.boundary = boundary;
            if (h == 260) g.dt = 0.9f;
            tp::Grid feed(w, h, 0.05f);
            feed.at(w / 2, h / 2) = 0.03f;
            g.feed_map = w > 1000 ? &feed : nullptr;
            tp::ReactionDiffusion fused(g, tp::rd_initial_spots(w, h, 2, 0, 6));
            tp::ReactionDiffusion single = fused;
            fused.step(23);
            for (int i = 0; i < 23; ++i) single.step(1);
            const size_t bytes = size_t(w) * h * 4;
            EXPECT_EQ(0, std::memcmp(fused.state().a.values.data(), single.state().a.values.data(), bytes)) << w;
            EXPECT_EQ(0, std::memcmp(fused.state().b.values.data(), single.state().b.values.data(), bytes)) << w;
        }
    }
}

TEST(ProceduralRd, EveryPresetStaysFiniteAndInUnitRange) {
    for (const tp::RdPreset& p : tp::rd_presets()) {
        tp::GrayScott g;
        g.feed = p.feed;
        g.kill = p.kill;
        const tp::RdState s = run(g, tp::rd_initial_spots(64, 64, 9), 1500);
        for (const tp::Grid* grid : {&s.a, &s.b})
            for (float v : grid->values) {
                ASSERT_TRUE(std::isfinite(v)) << p.name;
                ASSERT_GE(v, 0.0f) << p.name;
                ASSERT_LE(v, 1.0f) << p.name;
            }
    }
}

TEST(ProceduralRd, SpotsPresetGrowsSeparateSpots) {
    const tp::RdState s = run(preset("spots"), tp::rd_initial_spots(128, 128, 1), 5000);
    const Blobs b = blobs(s.b, 0.2f);
    EXPECT_GE(b.count, 15);
    EXPECT_LE(b.count, 150);
    EXPECT_LT(b.largest, 128 * 128 / 50);  // each spot is small: no blob covers 2% of the grid
}

TEST(ProceduralRd, StripesPresetGrowsLongConnectedStripes) {
    const tp::RdState s = run(preset("stripes"), tp::rd_initial_spots(128, 128, 1), 5000);
    const Blobs b = blobs(s.b, 0.2f);
    EXPECT_LE(b.count, 10);
    EXPECT_GT(b.largest, 128 * 128 / 10);  // stripes join into large winding regions
}

// With anisotropy > 0 the x neighbours weigh more, so the stripes stretch along x: B varies
// much more from row to row than from column to column.
TEST(ProceduralRd, AnisotropyAlignsStripes) {
    tp::GrayScott g = preset("stripes");
    g.anisotropy = 0.8f;
    const tp::RdState s = run(g, tp::rd_initial_spots(96, 96, 4), 4000);
    double along_x = 0, along_y = 0;
    for (int y = 0; y < 96; ++y)
        for (int x = 0; x < 96; ++x) {
            along_x += std::abs(s.b.at((x + 1) % 96, y) - s.b.at(x, y));
            along_y += std::abs(s.b.at(x, (y + 1) % 96) - s.b.at(x, y));
        }
    EXPECT_GT(along_y, 1.5 * along_x);
}

// A decayed B field shrinks geometrically; with FTZ/DAZ in the step it goes from normal
// floats straight to zero and never holds a denormal.
TEST(ProceduralRd, DecayedGridHoldsNoDenormals) {
    tp::RdState s{tp::Grid(64, 8, 1.0f), tp::Grid(64, 8, 1e-30f)};
    const tp::RdState out = run(preset("spots"), s, 300);  // 1e-30 * 0.9^300 is far below 1e-38
    for (float v : out.b.values) {
        EXPECT_TRUE(v == 0.0f || std::abs(v) >= FLT_MIN) << v;
    }
}

TEST(ProceduralRd, BadParametersAreRejected) {
    tp::GrayScott g;
    g.dt = 2.0f;  // Da * dt * 1.6 = 3.2 > 2
    EXPECT_THROW(tp::validate(g, 8, 8), std::invalid_argument);
    EXPECT_NEAR(tp::max_stable_dt(tp::GrayScott{}), 1.25f, 1e-6f);
    g = {};
    g.feed = std::nanf("");
    EXPECT_THROW(tp::validate(g, 8, 8), std::invalid_argument);
    g = {};
    EXPECT_THROW(tp::validate(g, 0, 8), std::invalid_argument);
    const tp::Grid wrong(4, 4, 0.05f);
    g.feed_map = &wrong;
    EXPECT_THROW(tp::validate(g, 8, 8), std::invalid_argument);
    EXPECT_EQ(tp::find_rd_preset("no-such-pattern"), nullptr);
    EXPECT_NE(tp::rd_preset_names().find("stripes"), std::string::npos);
}

TEST(ProceduralRd, ColourRampMapsEmptyAndPatternedCells) {
    tp::RdState s{tp::Grid(2, 1, 1.0f), tp::Grid(2, 1, 0.0f)};
    s.a.at(1, 0) = 0.2f;
    s.b.at(1, 0) = 0.4f;  // A - B < 0: the dark end of the ramp
    const std::vector<uint8_t> rgb = tp::rd_colorize(s);
    ASSERT_EQ(rgb.size(), 6u);
    const auto ramp = tp::default_rd_ramp();
    EXPECT_EQ(rgb[0], uint8_t(std::lround(ramp.back().rgb[0] * 255)));
    EXPECT_EQ(rgb[3], uint8_t(std::lround(ramp.front().rgb[0] * 255)));
}
