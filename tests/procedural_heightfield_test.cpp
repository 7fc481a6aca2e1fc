// Heightfields and normal maps: tileable maps wrap seamlessly, rows agree with the scalar
// fBm, output is identical for 1 and 2 threads, and normal maps are exact on flat and planar
// heights and agree with the analytic terrain gradient.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <cstring>

#include <glm/geometric.hpp>

#include "procedural/heightfield.h"
#include "procedural/normal_map.h"

namespace tp = tessera::procedural;

TEST(ProceduralHeightfield, RowsMatchScalarFbmAndTile) {
    tp::HeightfieldParams p;
    p.fractal = {6, 2.0f, 0.5f, 17};
    p.cells = 3;
    const int w = 96, h = 64;  // cells_y = round(3 * 64 / 96) = 2
    const tp::Grid g = tp::generate_heightfield(w, h, p);
    const float sx = 3.0f / w, sy = 2.0f / h;
    for (int y = 0; y < h; y += 7)
        for (int x = 0; x < w; x += 5) {
            const float ref = 0.5f * tp::fbm_periodic({x * sx, y * sy}, {3, 2}, p.fractal).value + 0.5f;
            ASSERT_NEAR(g.at(x, y), ref, 1e-5f);
        }
    // Left edge continues the right edge: the texel one past the right edge is column 0.
    for (int y = 0; y < h; ++y) {
        const float beyond = 0.5f * tp::fbm_periodic({w * sx, y * sy}, {3, 2}, p.fractal).value + 0.5f;
        EXPECT_NEAR(beyond, g.at(0, y), 1e-5f);
    }
    for (int x = 0; x < w; ++x) {
        const float beyond = 0.5f * tp::fbm_periodic({x * sx, h * sy}, {3, 2}, p.fractal).value + 0.5f;
        EXPECT_NEAR(beyond, g.at(x, 0), 1e-5f);
    }
    for (float v : g.values) {
        ASSERT_GE(v, 0.0f);
        ASSERT_LE(v, 1.0f);
    }
}

TEST(ProceduralHeightfield, IdenticalForOneAndTwoThreads) {
    for (tp::Relief relief : {tp::Relief::fbm, tp::Relief::ridged, tp::Relief::warped, tp::Relief::dunes}) {
        tp::HeightfieldParams p;
        p.relief = relief;
        p.fractal.seed = 5;
        tp::Grid one, two;
        {
            tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
            one = tp::generate_heightfield(123, 77, p);
        }
        {
            tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
            two = tp::generate_heightfield(123, 77, p);
        }
        EXPECT_EQ(0, std::memcmp(one.values.data(), two.values.data(), one.size() * 4)) << int(relief);
        const auto [lo, hi] = std::minmax_element(one.values.begin(), one.values.end());
        EXPECT_LT(*lo, *hi) << "relief " << int(relief) << " is flat";
    }
}

TEST(ProceduralHeightfield, NormalizeSpansZeroToOne) {
    tp::Grid g = tp::generate_heightfield(64, 64, {});
    tp::normalize_heights(g);
    const auto [lo, hi] = std::minmax_element(g.values.begin(), g.values.end());
    EXPECT_EQ(*lo, 0.0f);
    EXPECT_FLOAT_EQ(*hi, 1.0f);
    EXPECT_THROW(tp::generate_heightfield(0, 64, {}), std::invalid_argument);
    tp::HeightfieldParams bad;
    bad.fractal.octaves = 0;
    EXPECT_THROW(tp::generate_heightfield(8, 8, bad), std::invalid_argument);
}

TEST(ProceduralNormalMap, FlatHeightsGiveStraightUp) {
    const tp::Grid flat(17, 9, 0.37f);
    for (tp::Boundary b : {tp::Boundary::periodic, tp::Boundary::clamped}) {
        const tp::NormalMap n = tp::normal_map(flat, 10.0f, b);
        for (size_t i = 0; i < n.xyz.size(); i += 3) {
            ASSERT_EQ(n.xyz[i], 0.0f);
            ASSERT_EQ(n.xyz[i + 1], 0.0f);
            ASSERT_EQ(n.xyz[i + 2], 1.0f);
        }
        const std::vector<uint8_t> rgb = tp::encode_normals_rgb8(n);
        EXPECT_EQ(rgb[0], 128);
        EXPECT_EQ(rgb[1], 128);
        EXPECT_EQ(rgb[2], 255);
    }
}

// A plane rising along +x tilts normals towards -x; rising down the rows (towards -v) tilts
// them towards +y (green up, OpenGL convention).
TEST(ProceduralNormalMap, PlanesTiltTheRightWay) {
    tp::Grid ramp_x(8, 8), ramp_rows(8, 8);
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x) {
            ramp_x.at(x, y) = 0.1f * x;
            ramp_rows.at(x, y) = 0.1f * y;
        }
    const tp::NormalMap nx = tp::normal_map(ramp_x, 2.0f, tp::Boundary::clamped);
    const tp::NormalMap ny = tp::normal_map(ramp_rows, 2.0f, tp::Boundary::clamped);
    const size_t centre = (4 * 8 + 4) * 3;
    const float len = std::sqrt(0.2f * 0.2f + 1.0f);
    EXPECT_NEAR(nx.xyz[centre + 0], -0.2f / len, 1e-6f);
    EXPECT_NEAR(nx.xyz[centre + 1], 0.0f, 1e-6f);
    EXPECT_NEAR(ny.xyz[centre + 1], 0.2f / len, 1e-6f);
    EXPECT_NEAR(ny.xyz[centre + 2], 1.0f / len, 1e-6f);
}

// Normals of a smooth tileable heightfield agree with the analytic fBm gradient (chain rule:
// texel spacing sx lattice units, heights 0.5 fbm + 0.5), also across the wrapped edge.
TEST(ProceduralNormalMap, AgreesWithAnalyticGradient) {
    tp::HeightfieldParams p;
    p.fractal = {2, 2.0f, 0.5f, 3};
    p.cells = 2;
    const int n = 256;
    const tp::Grid g = tp::generate_heightfield(n, n, p);
    const float strength = 40.0f, s = 2.0f / n;
    const tp::NormalMap normals = tp::normal_map(g, strength, tp::Boundary::periodic);
    for (int y : {0, 31, 128, 255})
        for (int x : {0, 17, 200, 255}) {
            const tp::Noise2 f = tp::fbm_periodic({x * s, y * s}, {2, 2}, p.fractal);
            const float dx = 0.5f * f.gradient.x * s, drow = 0.5f * f.gradient.y * s;
            const glm::vec3 expected = glm::normalize(glm::vec3(-strength * dx, strength * drow, 1.0f));
            const float* got = &normals.xyz[(size_t(y) * n + x) * 3];
            EXPECT_NEAR(got[0], expected.x, 2e-3f) << x << "," << y;
            EXPECT_NEAR(got[1], expected.y, 2e-3f) << x << "," << y;
        }
}
