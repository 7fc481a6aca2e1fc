// Fog: the closed-form optical depth against numerical quadrature (constant and exponential
// height fog, including horizontal and near-horizontal rays), the background at infinity, and
// refusal of bad parameters.
#include "raster/march/fog.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>

using namespace tessera::march;

namespace {

// Composite Simpson on 10^5 intervals of e^{-b (o_y + t d_y - y0)} over [0, D], in double.
double quadrature(double b, double y0, double oy, double dy, double D) {
    const int n = 100000;
    const double h = D / n;
    double sum = 0.0;
    for (int i = 0; i <= n; ++i) {
        const double w = (i == 0 || i == n) ? 1.0 : (i % 2 ? 4.0 : 2.0);
        sum += w * std::exp(-b * (oy + i * h * dy - y0));
    }
    return sum * h / 3.0;
}

constexpr float kInf = std::numeric_limits<float>::infinity();

}  // namespace

TEST(MarchFog, HeightFogClosedFormMatchesQuadrature) {
    Fog fog;
    fog.density = glm::vec3(0.3f);
    fog.base_height = 0.5f;
    for (float b : {0.0f, 0.1f, 1.0f, 4.0f})
        for (float dy : {-0.9f, -0.3f, -1e-3f, -1e-6f, 0.0f, 1e-7f, 1e-5f, 0.2f, 0.99f})
            for (float D : {0.5f, 7.0f, 40.0f}) {
                fog.falloff = b;
                const float oy = 2.0f;
                const double reference = quadrature(b, 0.5, oy, dy, D);
                const double closed = fog.unit_optical_depth(oy, dy, D);
                if (reference > std::numeric_limits<float>::max()) {  // beyond float: opaque
                    EXPECT_EQ(closed, kInf);
                    continue;
                }
                EXPECT_NEAR(closed, reference, 1e-5 * reference)
                    << "b=" << b << " dy=" << dy << " D=" << D;
            }
}

TEST(MarchFog, TransmittanceAndInScatteringFollowTheSolution) {
    Fog fog;
    fog.density = {0.1f, 0.2f, 0.4f};  // coloured: red travels furthest
    fog.colour = {0.5f, 0.6f, 0.7f};
    const glm::vec3 t = fog.transmittance({0, 0, 0}, {1, 0, 0}, 5.0f);
    EXPECT_NEAR(t.x, std::exp(-0.5f), 1e-6f);
    EXPECT_NEAR(t.y, std::exp(-1.0f), 1e-6f);
    EXPECT_NEAR(t.z, std::exp(-2.0f), 1e-6f);
    const glm::vec3 seen = fog.apply({1, 1, 1}, {0, 0, 0}, {1, 0, 0}, 5.0f);
    EXPECT_NEAR(seen.z, t.z + (1 - t.z) * 0.7f, 1e-6f);
    // The background is infinitely far: constant fog hides it completely.
    const glm::vec3 bg = fog.apply({9, 9, 9}, {0, 0, 0}, {0, 1, 0}, kInf);
    EXPECT_EQ(bg, fog.colour);
    // Black fog only darkens.
    fog.colour = glm::vec3(0.0f);
    EXPECT_NEAR(fog.apply({1, 1, 1}, {0, 0, 0}, {1, 0, 0}, 5.0f).x, std::exp(-0.5f), 1e-6f);
}

TEST(MarchFog, HeightFogAtInfinity) {
    Fog fog;
    fog.density = glm::vec3(0.5f);
    fog.falloff = 2.0f;
    fog.base_height = 0.0f;
    // Upward: the integral converges to e^{-b o_y} / (b d_y).
    const float up = fog.unit_optical_depth(1.0f, 0.5f, kInf);
    EXPECT_NEAR(up, std::exp(-2.0f) / 1.0f, 1e-6f);
    EXPECT_NEAR(up, quadrature(2.0, 0.0, 1.0, 0.5, 60.0), 1e-5);
    // Level and downward rays never leave the fog.
    EXPECT_EQ(fog.unit_optical_depth(1.0f, 0.0f, kInf), kInf);
    EXPECT_EQ(fog.transmittance({0, 1, 0}, {0, -1, 0}, kInf), glm::vec3(0.0f));
    // A channel with no density stays clear even at infinity (no 0 * inf = NaN).
    fog.density = {0.0f, 0.5f, 0.0f};
    const glm::vec3 t = fog.transmittance({0, 1, 0}, {1, 0, 0}, kInf);
    EXPECT_EQ(t, glm::vec3(1.0f, 0.0f, 1.0f));
    EXPECT_EQ(fog.unit_optical_depth(1.0f, 0.3f, 0.0f), 0.0f);
}

TEST(MarchFog, BadParametersAreRefused) {
    Fog fog;
    fog.validate();
    EXPECT_FALSE(fog.enabled());
    fog.density = {0.1f, -0.1f, 0.1f};
    EXPECT_THROW(fog.validate(), std::invalid_argument);
    fog.density = {0.1f, std::nanf(""), 0.1f};
    EXPECT_THROW(fog.validate(), std::invalid_argument);
    fog.density = glm::vec3(0.1f);
    fog.falloff = -1.0f;
    EXPECT_THROW(fog.validate(), std::invalid_argument);
    fog.falloff = 0.0f;
    fog.colour = {kInf, 0, 0};
    EXPECT_THROW(fog.validate(), std::invalid_argument);
    fog.colour = glm::vec3(0.0f);
    fog.validate();
    EXPECT_TRUE(fog.enabled());
}
