// Where two cost curves cross (render/crossover.h), as `tessera compare --sweep` reports it.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "raster/render/crossover.h"

using tessera::render::CostSample;
using tessera::render::find_crossover;

namespace {

TEST(Crossover, PowerLawsCrossWhereTheyAreEqual) {
    // a = n / 1000 ms (linear), b = 2 sqrt(n) / 100 ms: equal at n = 400 (a: 0.4, b: 0.4).
    std::vector<CostSample> samples;
    for (double n : {10.0, 100.0, 1000.0, 10000.0}) samples.push_back({n, n / 1000.0, 2.0 * std::sqrt(n) / 100.0});
    const auto c = find_crossover(samples);
    ASSERT_TRUE(c);
    // Both are straight lines on log-log axes, so the interpolation is exact.
    EXPECT_NEAR(c->triangles, 400.0, 1e-6 * 400.0);
    EXPECT_TRUE(c->b_faster_above);
}

TEST(Crossover, TheDirectionFollowsWhoWinsAbove) {
    const std::vector<CostSample> samples = {{100, 5.0, 1.0}, {1000, 5.0, 10.0}};
    const auto c = find_crossover(samples);
    ASSERT_TRUE(c);
    EXPECT_FALSE(c->b_faster_above);  // b was faster below, a above
    EXPECT_GT(c->triangles, 100.0);
    EXPECT_LT(c->triangles, 1000.0);
    // log(b/a) goes from log(1/5) to log(2): t = log 5 / log 10, x = 10^(2 + t).
    EXPECT_NEAR(c->triangles, std::pow(10.0, 2.0 + std::log(5.0) / std::log(10.0)), 1e-6);
}

TEST(Crossover, NoneWhenOneSideWinsThroughout) {
    const std::vector<CostSample> samples = {{10, 1.0, 2.0}, {100, 2.0, 3.0}, {1000, 20.0, 21.0}};
    EXPECT_FALSE(find_crossover(samples));
    EXPECT_FALSE(find_crossover(std::vector<CostSample>{}));
    EXPECT_FALSE(find_crossover(std::vector<CostSample>{{10, 1.0, 0.5}}));
}

TEST(Crossover, AnEqualSampleIsTheCrossingOnlyWhenTheSidesSwap) {
    // Equal at 100 between a win of a and a win of b: the crossing is there, exactly.
    const std::vector<CostSample> swap = {{10, 1.0, 2.0}, {100, 3.0, 3.0}, {1000, 9.0, 4.0}};
    const auto c = find_crossover(swap);
    ASSERT_TRUE(c);
    EXPECT_EQ(c->triangles, 100.0);
    EXPECT_TRUE(c->b_faster_above);
    // Touching without swapping is no crossing.
    const std::vector<CostSample> touch = {{10, 1.0, 2.0}, {100, 3.0, 3.0}, {1000, 4.0, 9.0}};
    EXPECT_FALSE(find_crossover(touch));
}

TEST(Crossover, UnusableSamplesAreSkipped) {
    // A zero time, a zero count and a count that goes back tell nothing and are passed over;
    // the crossing is between the usable neighbours 10 and 1000.
    const std::vector<CostSample> samples = {
        {10, 1.0, 2.0}, {50, 0.0, 1.0}, {0, 1.0, 1.0}, {5, 3.0, 1.0}, {1000, 4.0, 2.0}};
    const auto c = find_crossover(samples);
    ASSERT_TRUE(c);
    EXPECT_GT(c->triangles, 10.0);
    EXPECT_LT(c->triangles, 1000.0);
    EXPECT_TRUE(c->b_faster_above);
}

}  // namespace
