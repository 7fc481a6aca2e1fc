// Metaball kernels and fields: the kernels' defining values, analytic against finite-difference
// derivatives, culling and the packet bound that change nothing but the cost, and refusal of
// bad balls.
#include "raster/march/metaball_field.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <stdexcept>

#include "procedural/hash.h"
#include "raster/march/bounds.h"
#include "raster/march/march.h"
#include "raster/march/march_surface.h"
#include "raster/march/metaball_orbits.h"
#include "raster/march/metaball_packet.h"
#include "raster/march/ray_generation.h"
#include "seeded_random.h"

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
            EXPECT_LE(glm::length(g - fd), 1e-3f * std::max(1.0f, glm::length(g)))
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
        MetaballPacket subset;
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
                    EXPECT_EQ(std::bit_cast<uint32_t>(b.t0), std::bit_cast<uint32_t>(segments.t0[i]));
                    EXPECT_EQ(std::bit_cast<uint32_t>(b.t1), std::bit_cast<uint32_t>(segments.t1[i]));
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

// A tile keeps every ball some ray through its pixels crosses (and the surface marches nothing
// where it keeps none): tiles of several sizes and places over a wide view, balls near and
// far, one of them behind the camera.
TEST(MarchMetaball, TileCullingKeepsEveryBallItsPixelsCross) {
    std::vector<Metaball> balls = orbiting_metaballs(6, 1.1f, 0.8f);
    balls.push_back({{2.5f, 1.5f, -1.0f}, 0.5f, 1.0f});
    balls.push_back({{0.0f, 0.5f, 9.0f}, 1.0f, 1.0f});   // behind the eye
    balls.push_back({{-40.0f, 0.0f, 0.0f}, 1.0f, 1.0f});  // far off to the side
    const MetaballField field(balls, MetaballStyle{});
    Camera camera;
    camera.eye = {0.0f, 0.5f, 5.0f};
    camera.aspect = 1.5f;
    camera.fovy_deg = 70.0f;
    const int W = 96, H = 64;
    const RayGenerator rays(camera, W, H);
    const MetaballSurface surface{field};
    int kept = 0, empty = 0;
    for (const int size : {7, 16, 33})
        for (int y0 = 0; y0 < H; y0 += size)
            for (int x0 = 0; x0 < W; x0 += size) {
                const TileRect rect{x0, y0, std::min(W, x0 + size), std::min(H, y0 + size)};
                MetaballSurface::Scratch scratch;
                empty += !surface.bind_tile(rays, rect, scratch);
                for (size_t b = 0; b < balls.size(); ++b) {
                    bool crossed = false;
                    for (int y = rect.y0; y < rect.y1 && !crossed; ++y)
                        for (int x = rect.x0; x < rect.x1 && !crossed; ++x)
                            crossed = !sphere_interval(camera.eye, rays.direction(x, y), balls[b].centre,
                                                       balls[b].radius, 100.0f).empty();
                    if (!crossed) continue;
                    bool found = false;
                    for (size_t k = 0; k < scratch.tile.size(); ++k) found |= scratch.tile.ball(k).centre == balls[b].centre;
                    ASSERT_TRUE(found) << "tile " << x0 << "," << y0 << " size " << size << " ball " << b;
                    ++kept;
                }
                EXPECT_LT(scratch.tile.size(), balls.size());
            }
    EXPECT_GT(kept, 20);
    EXPECT_GT(empty, 5);
}

namespace {

// A packet's culled field as the marcher sees it, counting the packet evaluations; with
// `kBounded` it also passes on the packet's bound (march_field.h: BoundedPacketField).
template <bool kBounded>
struct CountingPacket {
    const MetaballPacket& packet;
    int* calls;
    float value(glm::vec3 p) const { return packet.value(p); }
    glm::vec3 gradient(glm::vec3 p) const { return packet.gradient(p); }
    void values(const float* x, const float* y, const float* z, float* out) const {
        ++*calls;
        packet.values(x, y, z, out);
    }
    simd::vmask may_reach(simd::vfloat a, simd::vfloat b) const
        requires kBounded
    {
        return packet.may_reach(a, b);
    }
};

}  // namespace

// The bound is never tighter than the field as values() computes it: for random balls (some
// far from the origin, some with negative weights) and random stretches of random rays, with
// the threshold just below the largest sum a sample of the stretch reaches (so that sample
// has f >= 0), the stretch's lane is kept. With twice that threshold some lanes are dropped,
// so the check is not vacuous.
TEST(MarchMetaball, BoundKeepsEveryLaneWithASampleOnTheSurface) {
    test::Rng rng(5);
    int dropped = 0, checked = 0;
    constexpr int kEven = 257;
    for (int trial = 0; trial < 60; ++trial) {
        const MetaballKernel kernel = MetaballKernel(rng.uniform(0, 2));
        const glm::vec3 offset = trial % 3 == 0 ? glm::vec3(700.0f, -300.0f, 900.0f) : glm::vec3(0.0f);
        std::vector<Metaball> balls;
        for (int b = 0, n = int(rng.uniform(1, 6)); b < n; ++b)
            balls.push_back({offset + glm::vec3(rng.unit(), rng.unit(), rng.unit()) * 2.0f - 1.0f,
                             0.3f + 1.5f * rng.unit(), rng.chance(20) ? -0.5f * rng.unit() : 0.2f + rng.unit()});
        RayPacket rays;
        rays.count = kMarchLanes;
        const glm::vec3 eye = offset + glm::vec3(0.3f, 0.2f, 4.0f);
        for (int i = 0; i < kMarchLanes; ++i) {
            const glm::vec3 aim = offset + (glm::vec3(rng.unit(), rng.unit(), rng.unit()) * 2.4f - 1.2f);
            const glm::vec3 d = glm::normalize(aim - eye);
            rays.ox[i] = eye.x, rays.oy[i] = eye.y, rays.oz[i] = eye.z;
            rays.dx[i] = d.x, rays.dy[i] = d.y, rays.dz[i] = d.z;
        }
        const auto field_with = [&](float threshold) { return MetaballField(balls, MetaballStyle{kernel, threshold}); };
        MetaballPacket packet;
        PacketSegments segments;
        field_with(1.0f).cull(rays, 100.0f, packet, segments);
        // One stretch per lane: even samples, and each ball's closest approach within it.
        alignas(64) float from[kMarchLanes], to[kMarchLanes];
        for (int i = 0; i < kMarchLanes; ++i) {
            const float span = std::max(segments.t1[i] - segments.t0[i], 0.0f);
            from[i] = segments.t0[i] + span * 0.5f * rng.unit();
            to[i] = from[i] + span * rng.unit();
        }
        const int samples = kEven + int(balls.size());
        std::vector<float> t(size_t(samples) * kMarchLanes);
        for (int j = 0; j < samples; ++j)
            for (int i = 0; i < kMarchLanes; ++i) {
                const float closest = j < kEven ? 0.0f : glm::dot(balls[j - kEven].centre - eye, rays.direction(i));
                t[j * kMarchLanes + i] = j < kEven ? from[i] + (to[i] - from[i]) * float(j) / float(kEven - 1)
                                                   : std::clamp(closest, from[i], std::max(from[i], to[i]));
            }
        // The largest value of each lane's samples, made as march_packet makes them.
        const auto peaks = [&](const MetaballPacket& field, float* peak) {
            for (int i = 0; i < kMarchLanes; ++i) peak[i] = -INFINITY;
            for (int j = 0; j < samples; ++j) {
                alignas(64) float x[kMarchLanes], y[kMarchLanes], z[kMarchLanes], v[kMarchLanes];
                const float* tj = &t[j * kMarchLanes];
                for (int i = 0; i < kMarchLanes; ++i) {
                    x[i] = rays.ox[i] + rays.dx[i] * tj[i];
                    y[i] = rays.oy[i] + rays.dy[i] * tj[i];
                    z[i] = rays.oz[i] + rays.dz[i] * tj[i];
                }
                field.values(x, y, z, v);
                for (int i = 0; i < kMarchLanes; ++i)
                    if (tj[i] >= from[i] && tj[i] <= to[i]) peak[i] = std::max(peak[i], v[i]);
            }
        };
        float sums[kMarchLanes];
        peaks(packet, sums);  // f + 1
        for (int i = 0; i < kMarchLanes; ++i) {
            const float sum = sums[i] + 1.0f;
            if (!(sum > 1e-3f)) continue;
            for (const float threshold : {std::nextafter(sum, 0.0f), 2.0f * sum}) {
                MetaballPacket bounded;
                field_with(threshold).cull(rays, 100.0f, bounded, segments);
                const uint32_t kept = simd::bits(bounded.may_reach(simd::vfloat::load(from), simd::vfloat::load(to)));
                float peak[kMarchLanes];
                peaks(bounded, peak);
                if (peak[i] >= 0.0f) {
                    ASSERT_TRUE(kept >> i & 1u) << "trial " << trial << " lane " << i << " kernel " << int(kernel);
                    ++checked;
                } else {
                    dropped += !(kept >> i & 1u);
                }
            }
        }
    }
    EXPECT_GT(checked, 300);
    EXPECT_GT(dropped, 30);
}

// Marching a packet with its bound skips most samples of a view of the metaballs and finds
// every hit where the unbounded march does, bit for bit, with both step schedules, with and
// without refinement.
TEST(MarchMetaball, BoundedMarchSkipsSamplesAndChangesNoHit) {
    std::vector<Metaball> balls = orbiting_metaballs(7, 2.3f, 0.9f);
    const MetaballField field(balls, MetaballStyle{MetaballKernel::wyvill, 0.35f});
    Camera camera;
    camera.eye = {0.4f, 0.6f, 4.2f};
    camera.aspect = 1.0f;
    const int W = 48, H = 40;
    const RayGenerator generator(camera, W, H);
    for (StepStrategy strategy : {StepStrategy::uniform, StepStrategy::geometric})
        for (bool refine : {true, false}) {
            MarchSettings settings;
            settings.strategy = strategy;
            settings.steps = 96;
            settings.refine = refine;
            int bounded_calls = 0, plain_calls = 0, hits = 0;
            for (int y = 0; y < H; ++y)
                for (int x0 = 0; x0 < W; x0 += kMarchLanes) {
                    RayPacket rays;
                    generator.packet(x0, y, std::min(kMarchLanes, W - x0), rays);
                    MetaballPacket packet;
                    PacketSegments segments;
                    field.cull(rays, 20.0f, packet, segments);
                    alignas(64) float bounded[kMarchLanes], plain[kMarchLanes];
                    march_packet(CountingPacket<true>{packet, &bounded_calls}, rays, segments, settings, bounded);
                    march_packet(CountingPacket<false>{packet, &plain_calls}, rays, segments, settings, plain);
                    for (int i = 0; i < rays.count; ++i) {
                        ASSERT_EQ(std::bit_cast<uint32_t>(bounded[i]), std::bit_cast<uint32_t>(plain[i]))
                            << x0 + i << "," << y << " strategy " << int(strategy) << " refine " << refine;
                        hits += bounded[i] != kMiss;
                    }
                }
            EXPECT_GT(hits, W * H / 10);
            EXPECT_LT(bounded_calls, plain_calls / 2) << "strategy " << int(strategy) << " refine " << refine;
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
