// Thermal erosion: conserves material, flattens slopes steeper than the talus, leaves flat
// ground alone, and is bit-identical for 1 and 2 threads.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>
#include <cstring>

#include "procedural/erosion.h"
#include "procedural/heightfield.h"

namespace tp = tessera::procedural;

namespace {
double total(const tp::Grid& g) {
    double sum = 0;
    for (float v : g.values) sum += v;
    return sum;
}
float steepest(const tp::Grid& g) {
    float m = 0;
    for (int y = 0; y < g.height; ++y)
        for (int x = 0; x < g.width; ++x)
            m = std::max({m, std::abs(g.at(x, y) - g.at((x + 1) % g.width, y)),
                          std::abs(g.at(x, y) - g.at(x, (y + 1) % g.height))});
    return m;
}
}  // namespace

TEST(ProceduralErosion, ConservesMaterialAndFlattensSteepSlopes) {
    for (tp::Boundary b : {tp::Boundary::periodic, tp::Boundary::clamped}) {
        tp::HeightfieldParams p;
        p.cells = 8;
        tp::Grid g = tp::generate_heightfield(96, 64, p);
        const double before = total(g);
        const float steep_before = steepest(g);
        tp::ThermalErosion e;
        e.iterations = 60;
        e.talus = 0.01f;
        e.boundary = b;
        tp::erode_thermal(g, e);
        EXPECT_NEAR(total(g), before, 1e-6 * before);
        EXPECT_LT(steepest(g), 0.8f * steep_before);
    }
}

TEST(ProceduralErosion, FlatGroundStaysFlat) {
    tp::Grid g(20, 10, 0.3f);
    tp::erode_thermal(g, {});
    for (float v : g.values) ASSERT_EQ(v, 0.3f);
}

// A single spike spreads to its four neighbours: the exact Olsen step for one cell.
TEST(ProceduralErosion, SpikeShedsToItsNeighbours) {
    tp::Grid g(5, 5, 0.0f);
    g.at(2, 2) = 1.0f;
    tp::ThermalErosion e;
    e.iterations = 1;
    e.talus = 0.1f;
    e.rate = 0.5f;
    tp::erode_thermal(g, e);
    // d_max = 1, d_total = 4: the spike loses 0.5 * (1 - 0.1) = 0.45, each neighbour gets 0.1125.
    EXPECT_NEAR(g.at(2, 2), 0.55f, 1e-6f);
    EXPECT_NEAR(g.at(1, 2), 0.1125f, 1e-6f);
    EXPECT_NEAR(g.at(2, 3), 0.1125f, 1e-6f);
    EXPECT_EQ(g.at(1, 1), 0.0f);
}

TEST(ProceduralErosion, IdenticalForOneAndTwoThreads) {
    tp::Grid one = tp::generate_heightfield(130, 70, {}), two = one;
    tp::ThermalErosion e;
    e.iterations = 20;
    {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
        tp::erode_thermal(one, e);
    }
    {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
        tp::erode_thermal(two, e);
    }
    EXPECT_EQ(0, std::memcmp(one.values.data(), two.values.data(), one.size() * 4));
}

TEST(ProceduralErosion, BadParametersAreRejected) {
    tp::Grid g(4, 4);
    tp::ThermalErosion e;
    e.rate = 0.9f;
    EXPECT_THROW(tp::erode_thermal(g, e), std::invalid_argument);
    e = {};
    e.talus = std::nanf("");
    EXPECT_THROW(tp::erode_thermal(g, e), std::invalid_argument);
}
