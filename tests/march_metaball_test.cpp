// Metaball kernels and fields: the kernels' defining values, analytic against finite-difference
// derivatives, culling that changes nothing but the cost, and refusal of bad balls.
#include "raster/march/metaball_field.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "procedural/hash.h"
#include "raster/march/bounds.h"
#include "raster/march/march.h"
#include "raster/march/metaball_orbits.h"
#include "raster/march/ray_generation.h"

using namespace tessera;
using namespace tessera::march;

namespace {

template <class Kernel>
void expect_derivative_matches(const Kernel& kernel, const char* name) {
    // Central differences in double precision of the float kernel, away from the kinks at s = 1.
    for (double s = 0.02; s < 0.98; s += 0.01) {
        const double h = 1e-3;
        const double fd = (double(kernel.at(float(s + h)).value) - double(kernel.at(float(s - h)).value)) / (2 * h);
        EXPECT_NEAR(kernel.at(float(s)).d_ds, fd, 2e-3 * std::max(1.0, std::fabs(fd))) << name << " s=" << s;
    }
}

std::vector<Metaball> three_balls() {
    return {{{-0.6f, 0.0f, 0.0f}, 1.0f, 1.0f}, {{0.6f, 0.1f, 0.0f}, 1.2f, 1.0f}, {{0.0f, 0.7f, 0.3f}, 0.9f, 0.8f}};
}

}  // namespace

TEST(MarchMetaball, WyvillKernelDefiningValues) {
    EXPECT_FLOAT_EQ(WyvillKernel::at(0.0f).value, 1.0f);
    EXPECT_NEAR(WyvillKernel::at(0.25f).value, 0.5f, 1e-6f);  // r = R/2
    EXPECT_NEAR(WyvillKernel::at(1.0f - 1e-7f).value, 0.0f, 1e-6f);
    EXPECT_NEAR(WyvillKernel::at(1.0f - 1e-7f).d_ds, 0.0f, 1e-5f);
    EXPECT_EQ(WyvillKernel::at(1.5f).value, 0.0f);
}

TEST(MarchMetaball, PerlinAndBlinnKernelsAreOneAtTheCentreAndZeroAtTheSupport) {
    EXPECT_FLOAT_EQ(PerlinKernel::at(0.0f).value, 1.0f);
    EXPECT_NEAR(PerlinKernel::at(0.25f).value, 0.5f, 1e-6f);  // fade(1/2) = 1/2
    EXPECT_NEAR(PerlinKernel::at(1.0f - 1e-7f).value, 0.0f, 1e-6f);
    EXPECT_NEAR(PerlinKernel::at(1.0f - 1e-7f).d_ds, 0.0f, 1e-5f);
    const BlinnKernel blinn(std::log(1000.0f));
    EXPECT_FLOAT_EQ(blinn.at(0.0f).value, 1.0f);
    EXPECT_NEAR(blinn.at(1.0f - 1e-7f).value, 0.0f, 1e-6f);
    EXPECT_NEAR(blinn.at(1.0f - 1e-7f).d_ds, 0.0f, 1e-5f);
    // Away from the cut it is the exponential less its tangent line at the cut, renormalised.
    const float a = std::log(1000.0f);
    EXPECT_NEAR(blinn.at(0.5f).value, (std::exp(-0.5f * a) - 1e-3f * (1.0f + 0.5f * a)) / (1.0f - 1e-3f * (1.0f + a)), 1e-6f);
}

TEST(MarchMetaball, KernelDerivativesMatchFiniteDifferences) {
    expect_derivative_matches(WyvillKernel{}, "wyvill");
    expect_derivative_matches(PerlinKernel{}, "perlin");
    expect_derivative_matches(BlinnKernel(6.9f), "blinn");
}

TEST(MarchMetaball, FieldGradientMatchesFiniteDifferencesForEveryKernel) {
    procedural::SplitMix64 rng(11);
    for (MetaballKernel kernel : {MetaballKernel::blinn, MetaballKernel::perlin, MetaballKernel::wyvill}) {
        const MetaballField field(three_balls(), MetaballStyle{kernel, 0.5f});
        for (int i = 0; i < 500; ++i) {
            const glm::vec3 p(rng.next_float() * 3 - 1.5f, rng.next_float() * 3 - 1.5f, rng.next_float() * 3 - 1.5f);
            const float h = 2e-3f;
            const glm::vec3 fd((field.value(p + glm::vec3(h, 0, 0)) - field.value(p - glm::vec3(h, 0, 0))) / (2 * h),
                               (field.value(p + glm::vec3(0, h, 0)) - field.value(p - glm::vec3(0, h, 0))) / (2 * h),
                               (field.value(p + glm::vec3(0, 0, h)) - field.value(p - glm::vec3(0, 0, h))) / (2 * h));
            const glm::vec3 g = field.gradient(p);
            EXPECT_LE(glm::length(g - fd), 2e-3f * std::max(1.0f, glm::length(g)))
                << "kernel " << int(kernel) << " at " << p.x << "," << p.y << "," << p.z;
        }
    }
}

TEST(MarchMetaball, PacketValuesEqualScalarValues) {
    const MetaballField field(orbiting_metaballs(5, 1.3f), MetaballStyle{MetaballKernel::perlin, 0.4f});
    alignas(64) float x[kMarchLanes], y[kMarchLanes], z[kMarchLanes], v[kMarchLanes];
    for (int i = 0; i < kMarchLanes; ++i) {
        x[i] = -1.0f + 0.13f * i;
        y[i] = 0.05f * i;
        z[i] = 0.3f - 0.07f * i;
    }
    field.values(x, y, z, v);
    for (int i = 0; i < kMarchLanes; ++i) EXPECT_NEAR(v[i], field.value({x[i], y[i], z[i]}), 1e-6f);
}

TEST(MarchMetaball, CullingKeepsTheHitsAndDropsFarBalls) {
    std::vector<Metaball> balls = orbiting_metaballs(4, 0.7f);
    balls.push_back({{40.0f, 0.0f, 0.0f}, 1.0f, 1.0f});  // far off to the side: never seen
    Camera camera;
    camera.eye = {0.0f, 0.5f, 5.0f};
    camera.aspect = 1.0f;
    const RayGenerator generator(camera, 32, 32);
    MarchSettings settings;
    for (MetaballKernel kernel : {MetaballKernel::blinn, MetaballKernel::wyvill}) {
        const MetaballField field(balls, MetaballStyle{kernel, 0.5f});
        MetaballField subset;
        int hits = 0;
        for (int y = 0; y < 32; ++y)
            for (int x0 = 0; x0 < 32; x0 += kMarchLanes) {
                RayPacket packet;
                generator.packet(x0, y, std::min(kMarchLanes, 32 - x0), packet);
                PacketSegments segments;
                field.cull(packet, 100.0f, subset, segments);
                EXPECT_LT(subset.size(), balls.size());
                // Exactly the balls some ray crosses: the packet cone never drops one.
                size_t crossed = 0;
                for (const Metaball& b : balls) {
                    bool any = false;
                    for (int i = 0; i < packet.count; ++i)
                        any |= !sphere_interval(packet.origin(i), packet.direction(i), b.centre, b.radius, 100.0f).empty();
                    crossed += any;
                }
                EXPECT_EQ(subset.size(), crossed);
                float culled[kMarchLanes], full[kMarchLanes];
                march_packet(subset, packet, segments, settings, culled);
                march_packet(field, packet, segments, settings, full);
                for (int i = 0; i < packet.count; ++i) {
                    EXPECT_EQ(culled[i], full[i]);
                    const Interval b = field.bounds(packet.origin(i), packet.direction(i), 100.0f);
                    EXPECT_EQ(b.t0, segments.t0[i]);
                    const float ref = march_ray(field, packet.origin(i), packet.direction(i), b, settings);
                    if (ref == kMiss) {
                        EXPECT_EQ(culled[i], kMiss);
                    } else {
                        EXPECT_NEAR(culled[i], ref, 1e-5f);
                        ++hits;
                    }
                }
            }
        EXPECT_GT(hits, 20);
    }
}

TEST(MarchMetaball, BadBallsAndStylesAreRefused) {
    EXPECT_THROW(MetaballField({{{0, 0, 0}, 0.0f, 1.0f}}, {}), std::invalid_argument);
    EXPECT_THROW(MetaballField({{{std::nanf(""), 0, 0}, 1.0f, 1.0f}}, {}), std::invalid_argument);
    EXPECT_THROW(MetaballField({{{0, 0, 0}, 1.0f, INFINITY}}, {}), std::invalid_argument);
    EXPECT_THROW(MetaballField({}, MetaballStyle{MetaballKernel::wyvill, -0.5f}), std::invalid_argument);
    EXPECT_THROW(MetaballField({}, MetaballStyle{MetaballKernel::blinn, 0.5f, 0.0f}), std::invalid_argument);
    EXPECT_THROW(orbiting_metaballs(-1, 0.0f), std::invalid_argument);
    EXPECT_EQ(orbiting_metaballs(3, 2.0f).size(), 3u);
}
