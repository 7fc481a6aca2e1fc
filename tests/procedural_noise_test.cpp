// Noise and implicit fields: analytic gradients agree with central differences, ranges hold,
// periodic lattices tile, batch forms agree with single-point calls, and the 16-sine
// noise matches its formula evaluated literally.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <functional>
#include <memory>
#include <vector>

#include "procedural/dunes.h"
#include "procedural/field.h"
#include "procedural/fractal.h"
#include "procedural/fractal_batch.h"
#include "procedural/hash.h"
#include "procedural/noise.h"
#include "procedural/simd_math.h"

namespace tp = tessera::procedural;

namespace {

// Random points in [-range, range]^3 from a fixed stream.
std::vector<glm::vec3> points(int count, float range, uint64_t seed = 42) {
    tp::SplitMix64 rng(seed);
    std::vector<glm::vec3> out(count);
    for (auto& p : out)
        p = glm::vec3(rng.next_float(), rng.next_float(), rng.next_float()) * (2 * range) - range;
    return out;
}

// Central differences with one Richardson step, (4 D(h/2) - D(h)) / 3, which cancels the h^2
// truncation term (fractal octaves and dune ripples have large third derivatives). Float
// rounding leaves ~1e-4 of noise at h = 2e-3, so compare with a tolerance relative to the
// gradient's size.
constexpr float kStep = 2e-3f;
template <class F, class V>
float derivative(F f, V p, V axis) {
    const float wide = (f(p + axis * kStep).value - f(p - axis * kStep).value) / (2 * kStep);
    const float narrow = (f(p + axis * (kStep / 2)).value - f(p - axis * (kStep / 2)).value) / kStep;
    return (4 * narrow - wide) / 3;
}
void expect_close(float analytic, float numeric, float scale, const char* what, glm::vec3 p,
                  float tolerance = 3e-3f) {
    EXPECT_NEAR(analytic, numeric, tolerance * std::max(1.0f, scale))
        << what << " at (" << p.x << ", " << p.y << ", " << p.z << ")";
}

void check_gradient2(const std::function<tp::Noise2(glm::vec2)>& f, float range, const char* what,
                     int count = 2000, float tolerance = 3e-3f) {
    for (glm::vec3 q : points(count, range)) {
        const glm::vec2 p(q.x, q.y);
        const tp::Noise2 s = f(p);
        const float gx = derivative(f, p, glm::vec2(1, 0));
        const float gy = derivative(f, p, glm::vec2(0, 1));
        const float scale = std::abs(s.gradient.x) + std::abs(s.gradient.y);
        expect_close(s.gradient.x, gx, scale, what, q, tolerance);
        expect_close(s.gradient.y, gy, scale, what, q, tolerance);
    }
}

template <class F>
void check_gradient3(F f, float range, const char* what, int count = 2000) {
    for (glm::vec3 p : points(count, range)) {
        const auto s = f(p);
        const glm::vec3 g(derivative(f, p, glm::vec3(1, 0, 0)), derivative(f, p, glm::vec3(0, 1, 0)),
                          derivative(f, p, glm::vec3(0, 0, 1)));
        const float scale = std::abs(s.gradient.x) + std::abs(s.gradient.y) + std::abs(s.gradient.z);
        expect_close(s.gradient.x, g.x, scale, what, p);
        expect_close(s.gradient.y, g.y, scale, what, p);
        expect_close(s.gradient.z, g.z, scale, what, p);
    }
}

}  // namespace

TEST(ProceduralNoise, SinCosMatchesLibm) {
    float worst = 0;
    for (float x = -10000.0f; x <= 10000.0f; x += 0.37f) {
        float s, c;
        tp::sincos_approx(x, s, c);
        worst = std::max({worst, std::abs(s - float(std::sin(double(x)))),
                          std::abs(c - float(std::cos(double(x))))});
    }
    EXPECT_LT(worst, 2e-6f);
}

TEST(ProceduralNoise, FloorIntMatchesFloor) {
    for (float x : {-2.5f, -2.0f, -1e-7f, 0.0f, 0.5f, 3.0f, 1e6f + 0.5f, -1e6f - 0.5f})
        EXPECT_EQ(tp::floor_int(x), int(std::floor(x))) << x;
}

TEST(ProceduralNoise, ValueNoiseStaysInRangeAndIsNotConstant) {
    float lo = 1, hi = -1;
    for (glm::vec3 p : points(20000, 50)) {
        const float v = tp::value_noise(p, 7).value;
        const float w = tp::value_noise(glm::vec2(p.x, p.y), 7).value;
        lo = std::min({lo, v, w});
        hi = std::max({hi, v, w});
    }
    EXPECT_GE(lo, -1.0f);
    EXPECT_LE(hi, 1.0f);
    EXPECT_LT(lo, -0.6f);  // a broken hash (constant or few values) would not spread this far
    EXPECT_GT(hi, 0.6f);
}

TEST(ProceduralNoise, SeedsGiveDifferentNoise) {
    const glm::vec3 p(1.3f, 2.7f, -0.4f);
    EXPECT_NE(tp::value_noise(p, 1).value, tp::value_noise(p, 2).value);
    EXPECT_EQ(tp::value_noise(p, 1).value, tp::value_noise(p, 1).value);
}

TEST(ProceduralNoise, GradientsMatchFiniteDifferences) {
    check_gradient2([](glm::vec2 p) { return tp::value_noise(p, 3); }, 40, "value2");
    check_gradient2([](glm::vec2 p) { return tp::gradient_noise(p, 3); }, 40, "gradient2");
    check_gradient2([](glm::vec2 p) { return tp::value_noise_periodic(p, {5, 7}, 3); }, 40,
                    "value2 periodic");
    check_gradient3([](glm::vec3 p) { return tp::value_noise(p, 3); }, 40, "value3");
    check_gradient3([](glm::vec3 p) { return tp::gradient_noise(p, 3); }, 40, "gradient3");
}

TEST(ProceduralNoise, FractalGradientsMatchFiniteDifferences) {
    const tp::Fractal f{5, 2.0f, 0.5f, 11};
    check_gradient2([&](glm::vec2 p) { return tp::fbm(p, f); }, 8, "fbm2");
    check_gradient2([&](glm::vec2 p) { return tp::fbm_periodic(p, {4, 4}, f); }, 8, "fbm periodic");
    // Three chained fBm fields: the finite difference itself is less exact, hence 1e-2.
    check_gradient2([&](glm::vec2 p) { return tp::domain_warp(p, f, 0.8f); }, 8, "domain warp",
                    2000, 1e-2f);
    // Ripples 5x longer than the default so that h = 2e-3 resolves their profile.
    tp::Dunes dunes;
    dunes.ripple_wavelength = 0.3f;
    dunes.wind = glm::vec2(0.6f, 0.8f);
    check_gradient2([&](glm::vec2 p) { return tp::dunes(p, dunes); }, 8, "dunes");
    const tp::DuneWaves<tp::TorusLattice> tiled = tp::dune_waves(dunes, {5, 3});
    check_gradient2([&](glm::vec2 p) { return tp::dunes(p, dunes, tiled); }, 8, "dunes tiled");
    check_gradient2([&](glm::vec2 p) { return tp::domain_warp(p, f, 0.8f, tp::TorusLattice{{3, 4}}); }, 8,
                    "domain warp periodic", 2000, 1e-2f);
    check_gradient3([&](glm::vec3 p) { return tp::fbm(p, f); }, 8, "fbm3");
}

// The ridged sum has creases where an octave's noise crosses zero and kinks where a weight
// clamps; away from the creases (where a step of 2h cannot cross one) the gradient must
// match, except at the rare points next to a weight kink (under 3%).
TEST(ProceduralNoise, RidgedGradientMatchesAwayFromCreases) {
    const tp::Fractal f{4, 2.0f, 0.5f, 5};
    int checked = 0, mismatched = 0;
    for (glm::vec3 q : points(3000, 8)) {
        const glm::vec2 p(q.x, q.y);
        bool near_crease = false;
        float freq = 1;
        for (int i = 0; i < f.octaves; ++i, freq *= 2) {
            const tp::Noise2 n = tp::gradient_noise(p * freq, tp::octave_seed(f.seed, i));
            near_crease |= std::abs(n.value) < 4 * kStep * freq * (std::abs(n.gradient.x) + std::abs(n.gradient.y) + 1);
        }
        if (near_crease) continue;
        ++checked;
        const tp::Noise2 s = tp::ridged(p, f);
        auto r = [&](glm::vec2 at) { return tp::ridged(at, f); };
        const float gx = derivative(r, p, glm::vec2(1, 0));
        const float gy = derivative(r, p, glm::vec2(0, 1));
        const float tolerance = 3e-3f * std::max(1.0f, std::abs(s.gradient.x) + std::abs(s.gradient.y));
        mismatched += std::abs(s.gradient.x - gx) > tolerance || std::abs(s.gradient.y - gy) > tolerance;
    }
    EXPECT_GT(checked, 500);
    EXPECT_LT(mismatched, checked * 3 / 100);
}

// Tiled dune waves: whole numbers of crests and ripples across the tile on each axis, nearest to
// the requested wave vector; a wave longer than the tile becomes one wave across it; the noise
// lattices get whole cell counts of at least 2 per tile.
TEST(ProceduralNoise, TiledDuneWavesFitTheTile) {
    tp::Dunes d;
    d.wind = glm::vec2(0.8f, 0.6f);
    d.wavelength = 1.0f;
    d.ripple_wavelength = 0.06f;
    const tp::DuneWaves<tp::TorusLattice> w = tp::dune_waves(d, {4, 4});
    EXPECT_EQ(w.crest, glm::vec2(3.0f / 4, 2.0f / 4));      // (3.2, 2.4) waves -> (3, 2)
    EXPECT_EQ(w.ripple, glm::vec2(53.0f / 4, 40.0f / 4));   // (53.3, 40) -> (53, 40)
    EXPECT_EQ(w.bend_lattice.period, glm::ivec2(2, 2));     // 0.5 cells per unit * 4 = 2
    EXPECT_EQ(w.height_lattice.period, glm::ivec2(3, 3));   // 0.7 * 4 = 2.8 -> 3
    EXPECT_EQ(w.height_scale, glm::vec2(0.75f));
    d.wavelength = 20.0f;
    d.wind = glm::vec2(0.0f, -1.0f);
    EXPECT_EQ(tp::dune_waves(d, {4, 2}).crest, glm::vec2(0.0f, -0.5f));
}

TEST(ProceduralNoise, PeriodicNoiseTiles) {
    const glm::ivec2 period(6, 4);
    const tp::Fractal f{4, 2.0f, 0.5f, 9};
    for (glm::vec3 q : points(500, 3)) {
        const glm::vec2 p(q.x + 3, q.y + 3);
        const tp::Noise2 a = tp::fbm_periodic(p, period, f);
        const tp::Noise2 b = tp::fbm_periodic(p + glm::vec2(period.x, 0), period, f);
        const tp::Noise2 c = tp::fbm_periodic(p - glm::vec2(0, period.y), period, f);
        EXPECT_NEAR(a.value, b.value, 1e-5f);
        EXPECT_NEAR(a.value, c.value, 1e-5f);
        EXPECT_NEAR(a.gradient.x, b.gradient.x, 1e-3f);
    }
    // Ridged, warped and dune relief on repeating lattices wrap the same way, gradients too.
    const tp::TorusLattice lattice{period};
    tp::Dunes d;
    d.wind = glm::vec2(0.6f, -0.8f);
    d.wavelength = 0.45f;
    const tp::DuneWaves<tp::TorusLattice> waves = tp::dune_waves(d, period);
    const std::function<tp::Noise2(glm::vec2)> reliefs[] = {
        [&](glm::vec2 p) { return tp::ridged(p, f, lattice); },
        [&](glm::vec2 p) { return tp::domain_warp(p, f, 0.7f, lattice); },
        [&](glm::vec2 p) { return tp::dunes(p, d, waves); }};
    for (const auto& relief : reliefs)
        for (glm::vec3 q : points(300, 3)) {
            const glm::vec2 p(q.x + 3, q.y + 3);
            const tp::Noise2 a = relief(p), b = relief(p + glm::vec2(period.x, 0));
            const tp::Noise2 c = relief(p - glm::vec2(0, period.y));
            EXPECT_NEAR(a.value, b.value, 1e-4f);
            EXPECT_NEAR(a.value, c.value, 1e-4f);
            EXPECT_NEAR(a.gradient.x, b.gradient.x, 1e-2f * std::max(1.0f, std::abs(a.gradient.x)));
            EXPECT_NEAR(a.gradient.y, c.gradient.y, 1e-2f * std::max(1.0f, std::abs(a.gradient.y)));
        }
}

TEST(ProceduralNoise, BatchesMatchSinglePoints) {
    const auto ps = points(1000, 30);
    std::vector<float> x, y, z;
    for (auto p : ps) x.push_back(p.x), y.push_back(p.y), z.push_back(p.z);
    std::vector<float> v(ps.size()), gx(ps.size()), gy(ps.size()), gz(ps.size());

    // Bit for bit, with gradients and values only; and the 3-D fBm (lacunarity 2.5).
    const auto same = [](float a, float b) { return std::bit_cast<uint32_t>(a) == std::bit_cast<uint32_t>(b); };
    const tp::Fractal f{4, 2.5f, 0.5f, 1};
    for (int kind = 0; kind < 3; ++kind) {
        std::vector<float> values_only(ps.size());
        const auto run = [&](float* value, float* dx, float* dy, float* dz) {
            if (kind == 0) tp::value_noise_batch(4, ps.size(), x.data(), y.data(), z.data(), value, dx, dy, dz);
            if (kind == 1) tp::gradient_noise_batch(4, ps.size(), x.data(), y.data(), z.data(), value, dx, dy, dz);
            if (kind == 2) tp::fbm_batch(f, ps.size(), x.data(), y.data(), z.data(), value, dx, dy, dz);
        };
        run(v.data(), gx.data(), gy.data(), gz.data());
        run(values_only.data(), nullptr, nullptr, nullptr);
        for (size_t i = 0; i < ps.size(); ++i) {
            const tp::Noise3 s = kind == 0 ? tp::value_noise(ps[i], 4) : kind == 1 ? tp::gradient_noise(ps[i], 4) : tp::fbm(ps[i], f);
            ASSERT_TRUE(same(v[i], s.value) && same(values_only[i], s.value)) << kind << " " << i;
            ASSERT_TRUE(same(gx[i], s.gradient.x) && same(gy[i], s.gradient.y) && same(gz[i], s.gradient.z)) << kind << " " << i;
        }
    }
}

// The 2-D fractal batches are the single-point sums in lanes: every relief, on the open and on a
// repeating lattice, with and without gradients, over a count that leaves partial blocks and
// points on both sides of the origin, equals the single call bit for bit (a lacunarity that is
// not a power of two, so each octave's scaling rounds).
TEST(ProceduralNoise, ReliefBatchesEqualSinglePointsBitForBit) {
    const auto ps = points(150, 40);
    const size_t n = ps.size();
    std::vector<float> x, y;
    for (auto p : ps) x.push_back(p.x), y.push_back(p.y);
    x[0] = y[0] = 0.0f;  // a lattice point
    x[1] = -1.0f;
    const tp::Fractal f{5, 3.0f, 0.45f, 9};
    const glm::ivec2 period(7, 5);
    tp::Dunes d;
    d.wind = glm::vec2(0.6f, -0.8f);
    d.wavelength = 3.5f;
    d.seed = 4;
    using Batch = std::function<void(const float*, const float*, float*, float*, float*)>;
    using Single = std::function<tp::Noise2(glm::vec2)>;
    const tp::OpenLattice open;
    const tp::TorusLattice torus{period};
    const tp::DuneWaves<tp::OpenLattice> open_waves = tp::dune_waves(d);
    const tp::DuneWaves<tp::TorusLattice> torus_waves = tp::dune_waves(d, period);
    const std::pair<Batch, Single> reliefs[] = {
        {[&](auto... a) { tp::fbm_batch(f, open, n, a...); }, [&](glm::vec2 p) { return tp::fbm(p, f, open); }},
        {[&](auto... a) { tp::fbm_batch(f, torus, n, a...); }, [&](glm::vec2 p) { return tp::fbm(p, f, torus); }},
        {[&](auto... a) { tp::ridged_batch(f, 1.0f, open, n, a...); }, [&](glm::vec2 p) { return tp::ridged(p, f, open); }},
        {[&](auto... a) { tp::ridged_batch(f, 0.9f, torus, n, a...); },
         [&](glm::vec2 p) { return tp::ridged(p, f, torus, 0.9f); }},
        {[&](auto... a) { tp::domain_warp_batch(f, 0.7f, open, n, a...); },
         [&](glm::vec2 p) { return tp::domain_warp(p, f, 0.7f, open); }},
        {[&](auto... a) { tp::domain_warp_batch(f, 0.7f, torus, n, a...); },
         [&](glm::vec2 p) { return tp::domain_warp(p, f, 0.7f, torus); }},
        {[&](auto... a) { tp::dunes_batch(d, open_waves, n, a...); }, [&](glm::vec2 p) { return tp::dunes(p, d, open_waves); }},
        {[&](auto... a) { tp::dunes_batch(d, torus_waves, n, a...); },
         [&](glm::vec2 p) { return tp::dunes(p, d, torus_waves); }},
    };
    int relief = 0;
    for (const auto& [batch, single] : reliefs) {
        std::vector<float> v(n), gx(n), gy(n), values_only(n);
        batch(x.data(), y.data(), v.data(), gx.data(), gy.data());
        batch(x.data(), y.data(), values_only.data(), nullptr, nullptr);
        for (size_t i = 0; i < n; ++i) {
            const tp::Noise2 s = single(glm::vec2(x[i], y[i]));
            ASSERT_EQ(std::bit_cast<uint32_t>(v[i]), std::bit_cast<uint32_t>(s.value)) << "relief " << relief << " point " << i;
            ASSERT_EQ(std::bit_cast<uint32_t>(values_only[i]), std::bit_cast<uint32_t>(s.value)) << relief << " " << i;
            ASSERT_EQ(std::bit_cast<uint32_t>(gx[i]), std::bit_cast<uint32_t>(s.gradient.x)) << relief << " " << i;
            ASSERT_EQ(std::bit_cast<uint32_t>(gy[i]), std::bit_cast<uint32_t>(s.gradient.y)) << relief << " " << i;
        }
        ++relief;
    }
}

TEST(ProceduralField, SineNoiseMatchesItsFormula) {
    const tp::SineNoiseField field;
    for (glm::vec3 r : points(300, 5)) {
        // The GLSL original, literally, in double precision.
        double s[3] = {7502, 22777, 4767}, w = 0;
        for (int i = 0; i < 16; ++i) {
            w += std::sin(((s[0] - 32768) * r.x * 40 + (s[1] - 32768) * r.y * 40 +
                           (s[2] - 32768) * r.z * 40) / 65536.0);
            for (double& c : s) c = std::fmod(c, 32768.0) * 2 + std::floor(c / 32768.0);
        }
        EXPECT_NEAR(field.value(r), w / 32 + 0.5 - r.y, 2e-5) << r.x << " " << r.y << " " << r.z;
    }
    check_gradient3([&](glm::vec3 p) { return field.sample(p); }, 5, "sine noise", 500);
}

TEST(ProceduralField, FieldGradientsAndBatches) {
    tp::TerrainParams terrain;
    terrain.frequency = 0.1f;
    terrain.amplitude = 3.0f;
    for (tp::Relief relief : {tp::Relief::fbm, tp::Relief::warped, tp::Relief::dunes}) {
        terrain.relief = relief;
        const tp::TerrainField field(terrain);
        check_gradient3([&](glm::vec3 p) { return field.sample(p); }, 20, "terrain", 300);
    }
    const tp::NoiseVolumeField volume({tp::Fractal{4, 2.0f, 0.5f, 3}, 0.5f, 0.5f, 0.5f});
    check_gradient3([&](glm::vec3 p) { return volume.sample(p); }, 10, "volume", 300);

    terrain.relief = tp::Relief::fbm;
    const tp::TerrainField field(terrain);
    const tp::SineNoiseField sine;
    const auto ps = points(700, 20);
    std::vector<float> x, y, z;
    for (auto p : ps) x.push_back(p.x), y.push_back(p.y), z.push_back(p.z);
    for (const tp::ImplicitField* f : std::initializer_list<const tp::ImplicitField*>{&field, &volume, &sine}) {
        std::vector<float> v(ps.size()), v2(ps.size()), gx(ps.size()), gy(ps.size()), gz(ps.size());
        f->sample_batch(ps.size(), x.data(), y.data(), z.data(), v.data(), gx.data(), gy.data(), gz.data());
        f->value_batch(ps.size(), x.data(), y.data(), z.data(), v2.data());
        for (size_t i = 0; i < ps.size(); ++i) {
            const tp::FieldSample s = f->sample(ps[i]);
            ASSERT_NEAR(v[i], s.value, 1e-5f * (1 + std::abs(s.value)));
            ASSERT_NEAR(v2[i], f->value(ps[i]), 1e-5f * (1 + std::abs(s.value)));
            ASSERT_NEAR(gx[i], s.gradient.x, 1e-4f * (1 + std::abs(s.gradient.x)));
            ASSERT_NEAR(gy[i], s.gradient.y, 1e-4f * (1 + std::abs(s.gradient.y)));
            ASSERT_NEAR(gz[i], s.gradient.z, 1e-4f * (1 + std::abs(s.gradient.z)));
        }
    }
}

// The fields' batch forms (what the marcher's packets call) give value() and sample() bit for
// bit: the terrain with every relief, the noise volume (a lacunarity that is not a power of
// two, so each octave's scaling rounds) and the 16-sine noise, at a count that is not a
// multiple of any block.
TEST(ProceduralField, FieldBatchesEqualSinglePointsBitForBit) {
    const auto ps = points(150, 30);
    const size_t n = ps.size();
    std::vector<float> x, y, z;
    for (auto p : ps) x.push_back(p.x), y.push_back(p.y * 0.1f), z.push_back(p.z);
    tp::TerrainParams terrain;
    terrain.fractal = {5, 2.5f, 0.5f, 3};
    terrain.frequency = 0.12f;
    terrain.amplitude = 1.6f;
    terrain.base = -0.4f;
    std::vector<std::unique_ptr<tp::ImplicitField>> fields;
    for (tp::Relief relief : {tp::Relief::fbm, tp::Relief::ridged, tp::Relief::warped, tp::Relief::dunes}) {
        terrain.relief = relief;
        fields.push_back(std::make_unique<tp::TerrainField>(terrain));
    }
    fields.push_back(std::make_unique<tp::NoiseVolumeField>(tp::VolumeParams{tp::Fractal{4, 2.5f, 0.5f, 3}, 0.7f, 0.5f, 0.5f}));
    fields.push_back(std::make_unique<tp::SineNoiseField>());
    for (size_t f = 0; f < fields.size(); ++f) {
        const tp::ImplicitField& field = *fields[f];
        std::vector<float> v(n), v2(n), gx(n), gy(n), gz(n);
        field.sample_batch(n, x.data(), y.data(), z.data(), v.data(), gx.data(), gy.data(), gz.data());
        field.value_batch(n, x.data(), y.data(), z.data(), v2.data());
        for (size_t i = 0; i < n; ++i) {
            const glm::vec3 p(x[i], y[i], z[i]);
            const tp::FieldSample s = field.sample(p);
            const float bits[][2] = {{v[i], s.value}, {v2[i], field.value(p)}, {gx[i], s.gradient.x},
                                     {gy[i], s.gradient.y}, {gz[i], s.gradient.z}};
            for (const auto& b : bits)
                ASSERT_EQ(std::bit_cast<uint32_t>(b[0]), std::bit_cast<uint32_t>(b[1])) << "field " << f << " point " << i;
        }
    }
}

TEST(ProceduralField, BadParametersAreRejected) {
    tp::TerrainParams terrain;
    terrain.frequency = std::nanf("");
    EXPECT_THROW(tp::TerrainField{terrain}, std::invalid_argument);
    terrain.frequency = 1;
    terrain.fractal.octaves = 0;
    EXPECT_THROW(tp::TerrainField{terrain}, std::invalid_argument);
}
