// The lane maths of raster/simd/lane_math.h: exponent_of, exp2_int and floor_of exactly,
// log2_positive, exp2_nonpositive and pow01 against std:: in double within their documented
// error, and every function giving the same bits as float (the scalar reference path) and as
// vfloat (kLanes at once), which the shading kernels' scalar/SIMD agreement rests on.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cfloat>
#include <cmath>
#include <iterator>
#include <limits>
#include <type_traits>

#include <glm/glm.hpp>

#include "raster/simd/lane_math.h"
#include "seeded_random.h"

namespace tessera::simd {
namespace {

using test::Rng;

struct alignas(64) Lanes {
    float v[kLanes];
};

// f evaluated on kLanes inputs as one vfloat; each lane must equal f on the float alone, bit
// for bit (both NaN counts as equal). Returns the float results.
template <class Fn>
Lanes expect_lanes_match_scalar(const Lanes& x, Fn f, const char* name) {
    Lanes vector_result, scalar_result;
    f(vfloat::load(x.v)).store(vector_result.v);
    for (int i = 0; i < kLanes; ++i) {
        scalar_result.v[i] = f(x.v[i]);
        const float a = vector_result.v[i], b = scalar_result.v[i];
        EXPECT_TRUE(std::bit_cast<uint32_t>(a) == std::bit_cast<uint32_t>(b) || (std::isnan(a) && std::isnan(b)))
            << name << "(" << x.v[i] << "): vfloat " << a << ", float " << b;
    }
    return scalar_result;
}

// A positive normal float with a random exponent in [lo, hi] and random mantissa bits.
float random_normal(Rng& rng, int lo, int hi) {
    const uint32_t exponent = uint32_t(rng.uniform(lo, hi) + 127);
    return std::bit_cast<float>((exponent << 23) | (uint32_t(rng.bits()) & 0x007FFFFFu));
}

constexpr int kRounds = 4000;

TEST(SimdLaneMath, ExponentOfSplitsNormalNumbersExactly) {
    Rng rng(21);
    for (int round = 0; round < kRounds; ++round) {
        Lanes x;
        for (float& v : x.v) v = rng.chance(10) ? std::ldexp(1.0f, int(rng.uniform(-126, 127))) : random_normal(rng, -126, 127);
        x.v[0] = round == 0 ? FLT_MIN : round == 1 ? FLT_MAX : x.v[0];
        Lanes mantissa_lanes;
        const Lanes e = expect_lanes_match_scalar(x, [&](auto v) {
            using F = decltype(v);
            F m;
            const F r = exponent_of(v, m);
            if constexpr (std::is_same_v<F, vfloat>) m.store(mantissa_lanes.v);
            return r;
        }, "exponent_of");
        for (int i = 0; i < kLanes; ++i) {
            float m;
            ASSERT_EQ(exponent_of(x.v[i], m), e.v[i]);
            ASSERT_EQ(e.v[i], float(std::ilogb(x.v[i]))) << x.v[i];
            ASSERT_GE(m, 1.0f);
            ASSERT_LT(m, 2.0f);
            ASSERT_EQ(std::ldexp(m, int(e.v[i])), x.v[i]);
            ASSERT_EQ(mantissa_lanes.v[i], m);
        }
    }
}

TEST(SimdLaneMath, Exp2IntAndFloorOfAreExact) {
    for (int n = -126; n <= 127; n += kLanes) {
        Lanes x;
        for (int i = 0; i < kLanes; ++i) x.v[i] = float(std::min(n + i, 127));
        const Lanes r = expect_lanes_match_scalar(x, [](auto v) { return exp2_int(v); }, "exp2_int");
        for (int i = 0; i < kLanes; ++i) ASSERT_EQ(r.v[i], std::ldexp(1.0f, int(x.v[i])));
    }
    Rng rng(22);
    for (int round = 0; round < kRounds; ++round) {
        Lanes x;
        for (float& v : x.v) {
            const float n = float(int32_t(rng.bits() >> 32));
            v = n * std::ldexp(1.0f, int(rng.uniform(-40, 0)));
        }
        x.v[0] = round % 3 == 0 ? -0.0f : round % 3 == 1 ? -0.5f : x.v[0];
        const Lanes f = expect_lanes_match_scalar(x, [](auto v) { return floor_of(v); }, "floor_of");
        const Lanes a = expect_lanes_match_scalar(x, [](auto v) { return abs_of(v); }, "abs_of");
        for (int i = 0; i < kLanes; ++i) {
            ASSERT_EQ(std::bit_cast<uint32_t>(f.v[i]), std::bit_cast<uint32_t>(std::floor(x.v[i]))) << x.v[i];
            ASSERT_EQ(std::bit_cast<uint32_t>(a.v[i]), std::bit_cast<uint32_t>(std::fabs(x.v[i]))) << x.v[i];
        }
    }
}

// log2_positive: absolute error < 2e-6 (the series' first term left out, largest at mantissas
// near 2), plus the final rounding of e + log2 m (half an ulp of the result); exact at powers
// of two.
TEST(SimdLaneMath, Log2PositiveWithinItsErrorBound) {
    Rng rng(23);
    double worst = 0.0;
    for (int round = 0; round < kRounds; ++round) {
        Lanes x;
        for (float& v : x.v) {
            switch (rng.uniform(0, 3)) {
                case 0: v = random_normal(rng, -126, 127); break;
                case 1: v = random_normal(rng, -2, 1); break;
                case 2: v = 1.0f + (rng.unit() - 0.5f) * 1e-3f; break;  // log2 near 0: absolute error
                default: v = std::ldexp(1.0f, int(rng.uniform(-126, 127))); break;
            }
        }
        const Lanes r = expect_lanes_match_scalar(x, [](auto v) { return log2_positive(v); }, "log2_positive");
        for (int i = 0; i < kLanes; ++i) {
            const double exact = std::log2(double(x.v[i]));
            const double error = std::fabs(double(r.v[i]) - exact);
            const double ulp = std::nextafter(std::fabs(r.v[i]), FLT_MAX) - std::fabs(r.v[i]);
            worst = std::max(worst, error - 0.5 * ulp);
            ASSERT_LE(error, 2e-6 + 0.5 * ulp) << "log2_positive(" << x.v[i] << ") = " << r.v[i];
            if ((std::bit_cast<uint32_t>(x.v[i]) & 0x007FFFFFu) == 0) {  // 2^k
                ASSERT_EQ(double(r.v[i]), exact);
            }
        }
    }
    EXPECT_GT(worst, 1.5e-6) << "inputs should approach the bound";
}

// exp2_nonpositive: relative error < 1e-6 over [-126, 0], exact at integers, 0 below -126.
TEST(SimdLaneMath, Exp2NonpositiveWithinItsErrorBound) {
    Rng rng(24);
    for (int round = 0; round < kRounds; ++round) {
        Lanes y;
        for (float& v : y.v) {
            switch (rng.uniform(0, 3)) {
                case 0: v = -126.0f * rng.unit(); break;
                case 1: v = -rng.unit(); break;
                case 2: v = -1e-6f * rng.unit(); break;
                default: v = -float(rng.uniform(0, 126)); break;
            }
        }
        const Lanes r = expect_lanes_match_scalar(y, [](auto v) { return exp2_nonpositive(v); }, "exp2_nonpositive");
        for (int i = 0; i < kLanes; ++i) {
            const double exact = std::exp2(double(y.v[i]));
            ASSERT_LE(std::fabs(double(r.v[i]) - exact), 1e-6 * exact) << "exp2_nonpositive(" << y.v[i] << ")";
            if (y.v[i] == std::floor(y.v[i])) {
                ASSERT_EQ(double(r.v[i]), exact);
            }
        }
    }
    Lanes edge;
    const float edges[] = {-126.0f, -126.00002f, -127.0f, -1000.0f, -std::numeric_limits<float>::infinity(), 0.0f, -0.0f};
    for (int i = 0; i < kLanes; ++i) edge.v[i] = edges[i % std::size(edges)];
    const Lanes r = expect_lanes_match_scalar(edge, [](auto v) { return exp2_nonpositive(v); }, "exp2_nonpositive");
    for (int i = 0; i < kLanes; ++i) EXPECT_EQ(r.v[i], edge.v[i] < -126.0f ? 0.0f : std::exp2(edge.v[i])) << edge.v[i];
}

// pow01(x, y) = 2^(y log2 x): exp2's relative 1e-6, plus log2's absolute 2e-6 (and the
// rounding of the product) scaled by y, carried through 2^: a relative ln 2 * that.
TEST(SimdLaneMath, Pow01WithinItsErrorBoundAndItsDefinedEdges) {
    Rng rng(25);
    for (int round = 0; round < kRounds; ++round) {
        Lanes x, y;
        for (int i = 0; i < kLanes; ++i) {
            x.v[i] = rng.chance(20) ? rng.unit() * 1e-3f : rng.unit();
            y.v[i] = rng.chance(20) ? rng.unit() * 2.0f : rng.unit() * 256.0f;
        }
        Lanes vector_result;
        pow01(vfloat::load(x.v), vfloat::load(y.v)).store(vector_result.v);
        for (int i = 0; i < kLanes; ++i) {
            const float r = pow01(x.v[i], y.v[i]);
            ASSERT_EQ(std::bit_cast<uint32_t>(vector_result.v[i]), std::bit_cast<uint32_t>(r));
            const double exact = std::pow(double(x.v[i]), double(y.v[i]));
            const double exponent = double(y.v[i]) * std::log2(double(x.v[i]));
            const double log_error = double(y.v[i]) * 2e-6 + std::fabs(exponent) * 0x1p-24;
            const double bound = exact * (1e-6 + std::log(2.0) * log_error * 1.01) + 0x1p-126;
            ASSERT_LE(std::fabs(double(r) - exact), bound) << "pow01(" << x.v[i] << ", " << y.v[i] << ")";
        }
    }
    // 0^y = 0 for y > 0, x^0 = 1 (0^0 too), 1^y = 1.
    EXPECT_EQ(pow01(0.0f, 3.0f), 0.0f);
    EXPECT_EQ(pow01(0.0f, 1e-6f), 0.0f);
    EXPECT_EQ(pow01(0.0f, 0.0f), 1.0f);
    EXPECT_EQ(pow01(0.3f, 0.0f), 1.0f);
    EXPECT_EQ(pow01(1.0f, 77.0f), 1.0f);
    EXPECT_EQ(pow01(0.5f, 3.0f), 0.125f);
    Lanes r;
    pow01(vfloat(0.0f), vfloat(0.0f)).store(r.v);
    EXPECT_EQ(r.v[0], 1.0f);
}

// The vector helpers: float and vfloat agree bit for bit; normalize_or gives unit vectors and
// its fallback exactly where the length is zero, tiny, huge or not finite.
TEST(SimdLaneMath, VectorHelpersMatchScalarAndNormalize) {
    Rng rng(26);
    const float inf = std::numeric_limits<float>::infinity(), nan = std::numeric_limits<float>::quiet_NaN();
    for (int round = 0; round < kRounds; ++round) {
        Lanes c[9];
        for (Lanes& l : c)
            for (float& v : l.v) {
                const float u = rng.unit() - 0.5f;
                v = u * std::ldexp(1.0f, int(rng.uniform(-70, 70)));
            }
        for (int i = 0; i < kLanes; ++i)
            if (rng.chance(10)) c[i % 3].v[i] = std::array{0.0f, inf, nan, 1e-20f}[rng.uniform(0, 3)];
        auto v3 = [&](int k, int i) { return V3<float>{c[k].v[i], c[k + 1].v[i], c[k + 2].v[i]}; };
        auto w3 = [&](int k) {
            return V3<vfloat>{vfloat::load(c[k].v), vfloat::load(c[k + 1].v), vfloat::load(c[k + 2].v)};
        };
        const V3<vfloat> a = w3(0), b = w3(3), fallback = w3(6);
        const V3<vfloat> n = normalize_or(a, fallback), x = cross(a, b), m = madd(a, b.x, fallback);
        const vfloat d = dot(a, b);
        Lanes out[10];
        n.x.store(out[0].v), n.y.store(out[1].v), n.z.store(out[2].v);
        x.x.store(out[3].v), x.y.store(out[4].v), x.z.store(out[5].v);
        m.x.store(out[6].v), m.y.store(out[7].v), m.z.store(out[8].v);
        d.store(out[9].v);
        for (int i = 0; i < kLanes; ++i) {
            const V3<float> sa = v3(0, i), sb = v3(3, i), sf = v3(6, i);
            const V3<float> sn = normalize_or(sa, sf), sx = cross(sa, sb), sm = madd(sa, sb.x, sf);
            const float expected[10] = {sn.x, sn.y, sn.z, sx.x, sx.y, sx.z, sm.x, sm.y, sm.z, dot(sa, sb)};
            for (int k = 0; k < 10; ++k)
                ASSERT_TRUE(std::bit_cast<uint32_t>(out[k].v[i]) == std::bit_cast<uint32_t>(expected[k]) ||
                            (std::isnan(out[k].v[i]) && std::isnan(expected[k])))
                    << "output " << k << " lane " << i;
            // Unit length where the squared length is a normal float, the fallback elsewhere.
            const double len2 = double(sa.x) * sa.x + double(sa.y) * sa.y + double(sa.z) * sa.z;
            if (len2 > 2e-30 && len2 < 2e38) {
                ASSERT_NEAR(std::sqrt(double(sn.x) * sn.x + double(sn.y) * sn.y + double(sn.z) * sn.z), 1.0, 1e-6);
                ASSERT_NEAR(double(sn.x) * std::sqrt(len2), double(sa.x), 1e-6 * std::sqrt(len2));
            } else if (!(len2 > 0.5e-30 && len2 < 4e38)) {
                ASSERT_EQ(sn.x, sf.x);
                ASSERT_EQ(sn.y, sf.y);
                ASSERT_EQ(sn.z, sf.z);
            }
        }
    }
}


// exp_of and expm1_of (double precision rounded once) against std::exp / std::expm1 in
// double rounded to float: equal but where the exact value lies within ~1e-13 of a rounding
// tie (never seen in these samples; a one-unit difference is allowed for it), and the same
// bits in lanes. The edges: underflow to 0, overflow to infinity, infinities, NaN.
TEST(SimdLaneMath, ExpOfIsTheRoundedExponential) {
    Rng rng(2121);
    int differing = 0;
    for (int round = 0; round < kRounds; ++round) {
        Lanes x;
        for (float& v : x.v) v = float(rng.unit() * 220.0 - 180.0);  // [-180, 40]
        if (round < 2)
            for (int i = 0; i < kLanes; ++i) {
                const float edges[] = {0.0f, -0.0f, 1e-30f, -1e-30f, 88.72f, 88.73f, 100.5f, -103.9f, -150.5f,
                                       std::numeric_limits<float>::infinity(), -std::numeric_limits<float>::infinity(),
                                       std::numeric_limits<float>::quiet_NaN(), 1e-4f, -1e-4f, 0.5f, -87.3f};
                x.v[i] = edges[(i + round * kLanes) % std::size(edges)];
            }
        const Lanes e = expect_lanes_match_scalar(x, [](auto v) { return exp_of(v); }, "exp_of");
        const Lanes m = expect_lanes_match_scalar(x, [](auto v) { return expm1_of(v); }, "expm1_of");
        for (int i = 0; i < kLanes; ++i) {
            const float v = x.v[i];
            if (std::isnan(v)) {
                EXPECT_TRUE(std::isnan(e.v[i]) && std::isnan(m.v[i]));
                continue;
            }
            const float want = float(std::exp(double(v)));
            const float got = e.v[i];
            if (got != want) {
                ++differing;
                ASSERT_EQ(std::nextafter(got, want), want) << "exp_of(" << v << ") = " << got << ", want " << want;
            }
            if (std::fabs(v) >= 1e-4f) {
                const float want_m1 = float(std::expm1(double(v)));
                ASSERT_TRUE(m.v[i] == want_m1 || std::nextafter(m.v[i], want_m1) == want_m1)
                    << "expm1_of(" << v << ") = " << m.v[i] << ", want " << want_m1;
            }
        }
    }
    EXPECT_LE(differing, 2);
}

// smoothstep: glm's value for float, and the same bits in lanes.
TEST(SimdLaneMath, SmoothstepIsGlmsInLanes) {
    Rng rng(77);
    for (int round = 0; round < kRounds / 4; ++round) {
        Lanes x;
        for (float& v : x.v) v = float(rng.unit() * 1.6 - 0.3);
        x.v[0] = round == 0 ? 0.75f : round == 1 ? 1.0f : round == 2 ? -0.0f : x.v[0];
        const Lanes s = expect_lanes_match_scalar(x, [](auto v) { return smoothstep(0.75f, 1.0f, v); }, "smoothstep");
        for (int i = 0; i < kLanes; ++i)
            ASSERT_EQ(std::bit_cast<uint32_t>(s.v[i]), std::bit_cast<uint32_t>(glm::smoothstep(0.75f, 1.0f, x.v[i])));
    }
}

}  // namespace
}  // namespace tessera::simd
