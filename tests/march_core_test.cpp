// The marcher against closed forms: a sphere written as an implicit field must be hit where
// the analytic ray-sphere intersection says, bisection must reach the requested tolerance,
// the packet path must agree with the scalar reference, and bad settings must be refused.
#include "raster/march/march.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>

#include "procedural/hash.h"
#include "raster/march/bounds.h"
#include "raster/march/ray_generation.h"
#include "raster/march/sphere_field.h"
#include "march_fixtures.h"

using namespace tessera;
using namespace tessera::march;
using namespace tessera::test;

namespace {

Camera sphere_camera() {
    Camera camera;
    camera.eye = {0.3f, 0.2f, 4.0f};
    camera.lookat = {0.0f, 0.0f, 0.0f};
    camera.aspect = 1.0f;
    camera.fovy_deg = 50.0f;
    return camera;
}

const SphereField kSphere{{0.1f, -0.2f, 0.0f}, 1.0f};

}  // namespace

TEST(MarchCore, SphereHitsMatchAnalyticDistanceForBothStrategies) {
    const Camera camera = sphere_camera();
    const RayGenerator rays(camera, 48, 48);
    for (StepStrategy strategy : {StepStrategy::uniform, StepStrategy::geometric}) {
        MarchSettings settings;
        settings.strategy = strategy;
        settings.tolerance = 1e-4f;
        settings.validate();
        int hits = 0;
        for (int y = 0; y < 48; ++y)
            for (int x = 0; x < 48; ++x) {
                const glm::vec3 d = rays.direction(x, y);
                const double exact = sphere_distance(glm::dvec3(camera.eye), glm::dvec3(d),
                                                     glm::dvec3(kSphere.centre), kSphere.radius);
                const float t = march_ray(kSphere, camera.eye, d, Interval{0.0f, 10.0f}, settings);
                if (std::isinf(exact)) {
                    EXPECT_EQ(t, kMiss) << x << "," << y;
                    continue;
                }
                // A ray whose chord is shorter than the step may tunnel; all others must hit.
                const glm::dvec3 oc = glm::dvec3(camera.eye - kSphere.centre);
                const double b = glm::dot(glm::dvec3(d), oc);
                const double chord = 2.0 * std::sqrt(b * b - glm::dot(oc, oc) + 1.0);
                if (chord < 0.2) continue;
                ASSERT_NE(t, kMiss) << x << "," << y;
                EXPECT_NEAR(t, exact, 0.5 * settings.tolerance + 1e-5) << x << "," << y;
                ++hits;
            }
        EXPECT_GT(hits, 300);
    }
}

TEST(MarchCore, BisectionReachesEachRequestedTolerance) {
    const glm::vec3 o(0.0f, 0.0f, 5.0f);
    procedural::SplitMix64 rng(7);
    for (float tolerance : {1e-1f, 1e-2f, 1e-3f, 1e-4f}) {
        MarchSettings settings;
        settings.steps = 16;  // coarse steps: the bracket starts ~0.4 wide
        settings.tolerance = tolerance;
        settings.validate();
        double worst = 0.0;
        for (int i = 0; i < 200; ++i) {
            const float u = rng.next_float() * 0.8f - 0.4f;
            const float v = rng.next_float() * 0.8f - 0.4f;
            const glm::vec3 d = glm::normalize(kSphere.centre + glm::vec3(u, v, 0.0f) - o);
            const double exact = sphere_distance(glm::dvec3(o), glm::dvec3(d), glm::dvec3(kSphere.centre), 1.0);
            ASSERT_FALSE(std::isinf(exact));
            const float t = march_ray(kSphere, o, d, Interval{0.0f, 7.0f}, settings);
            ASSERT_NE(t, kMiss);
            worst = std::max(worst, std::fabs(t - exact));
        }
        EXPECT_LE(worst, 0.5 * tolerance + 2e-6) << "tolerance " << tolerance;
    }
}

TEST(MarchCore, UnrefinedHitIsTheFirstInsideSample) {
    MarchSettings settings;
    settings.steps = 10;
    settings.refine = false;
    const glm::vec3 o(0.1f, -0.2f, 5.0f), d(0.0f, 0.0f, -1.0f);  // hits z = 1 at t = 4
    // Samples at 0.7, 1.4, ..., 4.2: the first inside one is 4.2.
    EXPECT_FLOAT_EQ(march_ray(kSphere, o, d, Interval{0.0f, 7.0f}, settings), 4.2f);
}

TEST(MarchCore, GeometricStepsSumToTheInterval) {
    MarchSettings settings;
    settings.strategy = StepStrategy::geometric;
    const MarchSettings::Schedule s = settings.schedule(Interval{2.0f, 582.7f});
    // The first step is 1/580 of the distance for +2 % over 128 steps.
    EXPECT_NEAR(s.first_step, 1.0, 2e-3);
    EXPECT_FLOAT_EQ(s.growth, 1.02f);
    double sum = 0.0, dt = s.first_step;
    for (int k = 0; k < 128; ++k, dt *= s.growth) sum += dt;
    EXPECT_NEAR(sum, 580.7, 1e-2);
}

TEST(MarchCore, UniformStepIsCappedByMaxStep) {
    MarchSettings settings;
    settings.max_step = 0.05f;  // a cap
    EXPECT_FLOAT_EQ(settings.schedule(Interval{0.0f, 100.0f}).first_step, 0.05f);
    EXPECT_FLOAT_EQ(settings.schedule(Interval{0.0f, 1.28f}).first_step, 0.01f);
}

TEST(MarchCore, PacketAgreesWithScalarReference) {
    const Camera camera = sphere_camera();
    const RayGenerator generator(camera, 37, 29);  // widths that leave partial packets
    for (StepStrategy strategy : {StepStrategy::uniform, StepStrategy::geometric}) {
        MarchSettings settings;
        settings.strategy = strategy;
        for (int y = 0; y < 29; ++y)
            for (int x0 = 0; x0 < 37; x0 += kMarchLanes) {
                RayPacket packet;
                const int count = std::min(kMarchLanes, 37 - x0);
                generator.packet(x0, y, count, packet);
                PacketSegments segments;
                for (int i = 0; i < kMarchLanes; ++i) {
                    const Interval s = sphere_interval(packet.origin(i), packet.direction(i),
                                                       kSphere.centre, kSphere.radius + 0.1f, 20.0f);
                    segments.t0[i] = s.t0;
                    segments.t1[i] = s.t1;
                }
                float t[kMarchLanes];
                march_packet(kSphere, packet, segments, settings, t);
                for (int i = 0; i < count; ++i) {
                    const glm::vec3 d = generator.direction(x0 + i, y);
                    EXPECT_NEAR(packet.dx[i], d.x, 1e-6f);
                    EXPECT_NEAR(packet.dy[i], d.y, 1e-6f);
                    EXPECT_NEAR(packet.dz[i], d.z, 1e-6f);
                    const float ref = march_ray(kSphere, packet.origin(i), packet.direction(i),
                                                Interval{segments.t0[i], segments.t1[i]}, settings);
                    if (ref == kMiss)
                        EXPECT_EQ(t[i], kMiss);
                    else
                        EXPECT_NEAR(t[i], ref, 1e-5f) << x0 + i << "," << y;
                }
            }
    }
}

TEST(MarchCore, RayStartingInsideHitsAtItsStart) {
    MarchSettings settings;
    EXPECT_EQ(march_ray(kSphere, kSphere.centre, {0.0f, 0.0f, 1.0f}, Interval{0.0f, 3.0f}, settings), 0.0f);
    EXPECT_EQ(march_ray(kSphere, {0, 0, 5}, {0, 0, -1}, Interval{}, settings), kMiss);
}

TEST(MarchCore, SlabClipFollowsTheSeed) {
    const Slab slab{0.0f, 1.0f};
    const Interval down = slab.clip({0.0f, 3.0f, 0.0f}, glm::normalize(glm::vec3(1, -1, 0)), 100.0f);
    EXPECT_NEAR(down.t0, 2.0f * std::sqrt(2.0f), 1e-5f);
    EXPECT_NEAR(down.t1, 3.0f * std::sqrt(2.0f), 1e-5f);
    EXPECT_TRUE(slab.clip({0.0f, 3.0f, 0.0f}, {1.0f, 0.0f, 0.0f}, 100.0f).empty());
    const Interval level = slab.clip({0.0f, 0.5f, 0.0f}, {1.0f, 0.0f, 0.0f}, 100.0f);
    EXPECT_EQ(level.t0, 0.0f);
    EXPECT_EQ(level.t1, 100.0f);
    EXPECT_TRUE(slab.clip({0.0f, 3.0f, 0.0f}, {0.0f, 1.0f, 0.0f}, 100.0f).empty());
    EXPECT_THROW((Slab{1.0f, 1.0f}.validate()), std::invalid_argument);
}

TEST(MarchCore, BadSettingsAreRefusedWithTheirName) {
    auto message = [](MarchSettings s) {
        try {
            s.validate();
        } catch (const std::invalid_argument& e) {
            return std::string(e.what());
        }
        return std::string("accepted");
    };
    MarchSettings s;
    s.steps = 0;
    EXPECT_NE(message(s).find("steps"), std::string::npos);
    s = {};
    s.tolerance = std::nanf("");
    EXPECT_NE(message(s).find("tolerance"), std::string::npos);
    s = {};
    s.tolerance = -1.0f;
    EXPECT_NE(message(s).find("tolerance"), std::string::npos);
    s = {};
    s.growth = 1.0f;
    EXPECT_NE(message(s).find("growth"), std::string::npos);
    s = {};
    s.max_step = std::nanf("");
    EXPECT_NE(message(s).find("max_step"), std::string::npos);
    EXPECT_EQ(message(MarchSettings{}), "accepted");
    EXPECT_THROW(RayGenerator(Camera{}, 0, 10), std::invalid_argument);
}
