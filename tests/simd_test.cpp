// The SIMD wrappers (raster/simd/simd.h and the back end this build selects) lane by lane
// against the scalar definition of each operation (raster/simd/scalar.h, plain C++): the
// arithmetic, compares, select, conversions and rounding, gather, interleaved loads and stores,
// compress, masked stores, the stamp layout, store_stamp_rows and stream_copy, over seeded
// random inputs (all 32-bit patterns: NaN, infinities and denormals included) and hand-picked
// edge values.
#include <gtest/gtest.h>

#include <bit>
#include <cfloat>
#include <climits>
#include <cmath>
#include <cstdint>
#include <algorithm>
#include <functional>
#include <iterator>
#include <limits>
#include <utility>
#include <vector>

#include "raster/core/aligned_vector.h"
#include "raster/simd/simd.h"
#include "seeded_random.h"

namespace tessera::simd {
namespace {

using test::Rng;

// One vector's worth of values, aligned for the aligned loads and stores of every back end.
template <class T>
struct alignas(64) Lanes {
    T v[kLanes];
    T& operator[](int i) { return v[i]; }
    const T& operator[](int i) const { return v[i]; }
};
vfloat load(const Lanes<float>& a) { return vfloat::load(a.v); }
vint load(const Lanes<int32_t>& a) { return vint::load(a.v); }
Lanes<float> lanes(vfloat a) {
    Lanes<float> out;
    a.store(out.v);
    return out;
}
Lanes<int32_t> lanes(vint a) {
    Lanes<int32_t> out;
    a.store(out.v);
    return out;
}
// A mask with lane i set where bit i of `pattern` is.
vmask mask_of(uint32_t pattern) {
    Lanes<int32_t> bit;
    for (int i = 0; i < kLanes; ++i) bit[i] = int32_t((pattern >> i) & 1u);
    return load(bit) == vint(1);
}
uint32_t all_bits() { return kLanes == 32 ? ~0u : (1u << kLanes) - 1; }

const float kNaN = std::numeric_limits<float>::quiet_NaN();
const float kInf = std::numeric_limits<float>::infinity();

// Values where IEEE arithmetic has special cases: zeros of both signs, denormals, the normal
// range's ends, infinities, NaN, halves (rounding ties) and integers around 2^23 and 2^24.
const std::vector<float> kSpecialFloats = {
    0.0f, -0.0f, 1.0f, -1.0f, 0.5f, -0.5f, 1.5f, -1.5f, 2.5f, -2.5f, 3.5f, 0.49999997f,
    FLT_TRUE_MIN, -FLT_TRUE_MIN, FLT_MIN, -FLT_MIN, FLT_MIN / 2.0f, 1e-40f, -3e-39f,
    FLT_MAX, -FLT_MAX, kInf, -kInf, kNaN, -kNaN, 8388607.5f, 8388608.0f, 16777216.0f, 16777215.0f,
    -8388609.0f, 1e10f, -1e-10f, 3.0f, 7.0f, 1.0f / 3.0f};

// Random floats: half arbitrary bit patterns (every class of value), half of moderate size,
// and one in eight a special value.
float random_float(Rng& rng) {
    const uint64_t r = rng.bits();
    if (r % 8 == 0) return kSpecialFloats[(r >> 8) % kSpecialFloats.size()];
    if (r % 2) return std::bit_cast<float>(uint32_t(r >> 32));
    return float(int32_t(r >> 32)) * 0x1p-20f;
}
int32_t random_int(Rng& rng) {
    static const int32_t special[] = {0, 1, -1, 2, INT32_MAX, INT32_MIN, INT32_MAX - 1, INT32_MIN + 1, 1 << 24,
                                      (1 << 24) + 1, -(1 << 24) - 1, 65535, -65536};
    const uint64_t r = rng.bits();
    if (r % 8 == 0) return special[(r >> 8) % std::size(special)];
    if (r % 2) return int32_t(uint32_t(r >> 32));
    return int32_t(r >> 40) - (1 << 23);
}
Lanes<float> random_floats(Rng& rng) {
    Lanes<float> a;
    for (int i = 0; i < kLanes; ++i) a[i] = random_float(rng);
    return a;
}
Lanes<int32_t> random_ints(Rng& rng) {
    Lanes<int32_t> a;
    for (int i = 0; i < kLanes; ++i) a[i] = random_int(rng);
    return a;
}

// The same float: equal bits, or both NaN (a NaN's payload is not specified across operations
// and compilers).
bool same_float(float a, float b) {
    return std::bit_cast<uint32_t>(a) == std::bit_cast<uint32_t>(b) || (std::isnan(a) && std::isnan(b));
}
// The same bits exactly (min, max and select pass an operand through unchanged).
bool same_bits(float a, float b) { return std::bit_cast<uint32_t>(a) == std::bit_cast<uint32_t>(b); }

constexpr int kRounds = 3000;

using FloatOp = std::function<vfloat(vfloat, vfloat)>;
using FloatRef = std::function<float(float, float)>;

void expect_float_op(const char* name, const FloatOp& op, const FloatRef& ref, bool exact_bits, uint64_t seed) {
    Rng rng(seed);
    // Every pair of special values once, then random lanes.
    std::vector<std::pair<float, float>> pairs;
    for (float a : kSpecialFloats)
        for (float b : kSpecialFloats) pairs.emplace_back(a, b);
    for (int round = 0; round < kRounds + int(pairs.size()) / kLanes + 1; ++round) {
        Lanes<float> a = random_floats(rng), b = random_floats(rng);
        for (int i = 0; i < kLanes; ++i) {
            const size_t k = size_t(round) * kLanes + i;
            if (k < pairs.size()) a[i] = pairs[k].first, b[i] = pairs[k].second;
        }
        const Lanes<float> r = lanes(op(load(a), load(b)));
        for (int i = 0; i < kLanes; ++i) {
            const float expected = ref(a[i], b[i]);
            ASSERT_TRUE(exact_bits ? same_bits(r[i], expected) : same_float(r[i], expected))
                << name << "(" << a[i] << ", " << b[i] << ") lane " << i << " = " << r[i] << ", expected "
                << expected;
        }
    }
}

TEST(Simd, FloatArithmeticIsIeeeSinglePrecisionPerLane) {
    expect_float_op("+", [](vfloat a, vfloat b) { return a + b; }, [](float a, float b) { return a + b; }, false, 1);
    expect_float_op("-", [](vfloat a, vfloat b) { return a - b; }, [](float a, float b) { return a - b; }, false, 2);
    expect_float_op("*", [](vfloat a, vfloat b) { return a * b; }, [](float a, float b) { return a * b; }, false, 3);
    expect_float_op("/", [](vfloat a, vfloat b) { return a / b; }, [](float a, float b) { return a / b; }, false, 4);
    expect_float_op("sqrt", [](vfloat a, vfloat) { return sqrt(a); }, [](float a, float) { return std::sqrt(a); },
                    false, 5);
}

TEST(Simd, FusedMultiplyAddRoundsOnce) {
    Rng rng(6);
    for (int round = 0; round < kRounds; ++round) {
        const Lanes<float> a = random_floats(rng), b = random_floats(rng), c = random_floats(rng);
        const Lanes<float> r = lanes(fma(load(a), load(b), load(c)));
        for (int i = 0; i < kLanes; ++i) ASSERT_TRUE(same_float(r[i], std::fma(a[i], b[i], c[i])));
    }
    // One rounding, not two: (1 + 2^-23)(1 - 2^-23) - 1 = -2^-46, which a * b rounds away.
    const float e = 0x1p-23f;
    const Lanes<float> r = lanes(fma(vfloat(1.0f + e), vfloat(1.0f - e), vfloat(-1.0f)));
    for (int i = 0; i < kLanes; ++i) EXPECT_EQ(r[i], -0x1p-46f);
}

// min/max: `a < b ? a : b` and `a > b ? a : b` exactly, so a NaN in either operand and the
// choice between -0 and +0 give the second operand (simd.h's promise, scalar.h's definition).
TEST(Simd, MinMaxReturnTheSecondOperandOnNaNAndEqualValues) {
    expect_float_op("min", [](vfloat a, vfloat b) { return min(a, b); },
                    [](float a, float b) { return a < b ? a : b; }, true, 7);
    expect_float_op("max", [](vfloat a, vfloat b) { return max(a, b); },
                    [](float a, float b) { return a > b ? a : b; }, true, 8);
    EXPECT_TRUE(same_bits(lanes(min(vfloat(-0.0f), vfloat(0.0f)))[0], 0.0f));
    EXPECT_TRUE(same_bits(lanes(max(vfloat(0.0f), vfloat(-0.0f)))[0], -0.0f));
    EXPECT_TRUE(std::isnan(lanes(min(vfloat(1.0f), vfloat(kNaN)))[0]));
    EXPECT_EQ(lanes(min(vfloat(kNaN), vfloat(1.0f)))[0], 1.0f);
}

TEST(Simd, FloatComparesAreOrderedAndFalseOnNaN) {
    Rng rng(9);
    for (int round = 0; round < kRounds; ++round) {
        Lanes<float> a = random_floats(rng), b = random_floats(rng);
        for (int i = 0; i < kLanes; i += 3) b[i] = a[i];  // equal values, NaN == NaN included
        uint32_t lt = 0, le = 0;
        for (int i = 0; i < kLanes; ++i) {
            lt |= uint32_t(a[i] < b[i]) << i;
            le |= uint32_t(a[i] <= b[i]) << i;
        }
        ASSERT_EQ(bits(load(a) < load(b)), lt);
        ASSERT_EQ(bits(load(a) <= load(b)), le);
    }
}

TEST(Simd, SelectPassesTheChosenLaneThrough) {
    Rng rng(10);
    for (int round = 0; round < kRounds; ++round) {
        const Lanes<float> a = random_floats(rng), b = random_floats(rng);
        const Lanes<int32_t> p = random_ints(rng), q = random_ints(rng);
        const uint32_t pattern = uint32_t(rng.bits()) & all_bits();
        const vmask m = mask_of(pattern);
        const Lanes<float> f = lanes(select(m, load(a), load(b)));
        const Lanes<int32_t> n = lanes(select(m, load(p), load(q)));
        for (int i = 0; i < kLanes; ++i) {
            const bool on = (pattern >> i) & 1u;
            ASSERT_TRUE(same_bits(f[i], on ? a[i] : b[i]));
            ASSERT_EQ(n[i], on ? p[i] : q[i]);
        }
    }
}

// Integer lanes wrap around like the hardware (scalar.h computes in uint32), shift right
// arithmetically by per-lane counts 0 .. 31 (and by constants: left, and right logically),
// and compare signed.
TEST(Simd, IntegerArithmeticWrapsAndComparesSigned) {
    Rng rng(11);
    for (int round = 0; round < kRounds; ++round) {
        const Lanes<int32_t> a = random_ints(rng), b = random_ints(rng);
        Lanes<int32_t> s;
        for (int i = 0; i < kLanes; ++i) s[i] = int32_t(rng.uniform(0, 31));
        const vint va = load(a), vb = load(b);
        const Lanes<int32_t> sum = lanes(va + vb), difference = lanes(va - vb), product = lanes(va * vb);
        const Lanes<int32_t> both = lanes(va & vb), either = lanes(va | vb), shifted = lanes(va >> load(s));
        const Lanes<int32_t> exclusive = lanes(va ^ vb), left = lanes(shift_left<7>(va)),
                             right = lanes(shift_right_logical<13>(va));
        const Lanes<int32_t> least = lanes(min(va, vb)), most = lanes(max(va, vb));
        ASSERT_EQ(first_lane(va), a[0]);
        for (int i = 0; i < kLanes; ++i) ASSERT_EQ(lane(va, i), a[i]);
        uint32_t ge = 0, lt = 0, eq = 0;
        for (int i = 0; i < kLanes; ++i) {
            ASSERT_EQ(sum[i], int32_t(uint32_t(a[i]) + uint32_t(b[i])));
            ASSERT_EQ(difference[i], int32_t(uint32_t(a[i]) - uint32_t(b[i])));
            ASSERT_EQ(product[i], int32_t(uint32_t(a[i]) * uint32_t(b[i])));
            ASSERT_EQ(both[i], a[i] & b[i]);
            ASSERT_EQ(either[i], a[i] | b[i]);
            ASSERT_EQ(shifted[i], a[i] >> s[i]) << a[i] << " >> " << s[i];
            ASSERT_EQ(exclusive[i], a[i] ^ b[i]);
            ASSERT_EQ(least[i], std::min(a[i], b[i]));
            ASSERT_EQ(most[i], std::max(a[i], b[i]));
            ASSERT_EQ(left[i], int32_t(uint32_t(a[i]) << 7));
            ASSERT_EQ(right[i], int32_t(uint32_t(a[i]) >> 13));
            ge |= uint32_t(a[i] >= b[i]) << i;
            lt |= uint32_t(a[i] < b[i]) << i;
            eq |= uint32_t(a[i] == b[i]) << i;
        }
        ASSERT_EQ(bits(va >= vb), ge);
        ASSERT_EQ(bits(va < vb), lt);
        ASSERT_EQ(bits(va == vb), eq);
        ASSERT_EQ(bits(va == va), all_bits());
    }
    EXPECT_EQ(lanes(vint(INT32_MAX) + vint(1))[0], INT32_MIN);
    EXPECT_EQ(lanes(vint(INT32_MIN) >> vint(31))[0], -1);
    EXPECT_EQ(lanes(vint(-7) >> vint(1))[0], -4);  // floors
}

TEST(Simd, MasksCombineAndReportTheirLanes) {
    Rng rng(12);
    EXPECT_EQ(bits(vmask(true)), all_bits());
    EXPECT_EQ(bits(vmask(false)), 0u);
    EXPECT_TRUE(all(vmask(true)));
    EXPECT_FALSE(any(vmask(false)));
    for (int round = 0; round < kRounds; ++round) {
        const uint32_t p = uint32_t(rng.bits()) & all_bits(), q = uint32_t(rng.bits()) & all_bits();
        const vmask a = mask_of(p), b = mask_of(q);
        ASSERT_EQ(bits(a), p);
        ASSERT_EQ(bits(a & b), p & q);
        ASSERT_EQ(bits(a | b), p | q);
        ASSERT_EQ(bits(andnot(a, b)), ~p & q);
        ASSERT_EQ(any(a), p != 0);
        ASSERT_EQ(all(a), p == all_bits());
        // Single-lane masks, where any/all are decided by one bit.
        const uint32_t one = 1u << rng.uniform(0, kLanes - 1);
        ASSERT_TRUE(any(mask_of(one)));
        ASSERT_EQ(all(mask_of(all_bits() & ~one)), false);
    }
}

// to_float rounds to nearest even (integers beyond 2^24); floor is std::floor (signed zero,
// infinities and NaN through); round_to_int rounds to nearest, ties to even, over the range
// of int32 (the wrappers do not define out-of-range or NaN conversions).
TEST(Simd, ConversionsAndRounding) {
    Rng rng(13);
    for (int round = 0; round < kRounds; ++round) {
        const Lanes<int32_t> n = random_ints(rng);
        const Lanes<float> f = lanes(to_float(load(n)));
        for (int i = 0; i < kLanes; ++i) ASSERT_TRUE(same_bits(f[i], float(n[i]))) << n[i];

        Lanes<float> x = random_floats(rng);
        const Lanes<float> floored = lanes(floor(load(x)));
        for (int i = 0; i < kLanes; ++i) ASSERT_TRUE(same_float(floored[i], std::floor(x[i]))) << x[i];

        for (int i = 0; i < kLanes; ++i) {
            // Within int32, with many exact halves.
            const float v = rng.chance(50) ? float(random_int(rng)) * 0x1p-8f : float(int32_t(rng.bits() >> 40) - (1 << 23)) + 0.5f;
            x[i] = std::fabs(v) < 2147483520.0f ? v : 0.0f;
        }
        const Lanes<int32_t> rounded = lanes(round_to_int(load(x)));
        for (int i = 0; i < kLanes; ++i) ASSERT_EQ(rounded[i], int32_t(std::nearbyint(x[i]))) << x[i];
    }
    const float halves[] = {0.5f, 1.5f, 2.5f, -0.5f, -1.5f, -2.5f, 8388607.5f, -8388607.5f, 0.49999997f, -0.0f};
    const int32_t even[] = {0, 2, 2, 0, -2, -2, 8388608, -8388608, 0, 0};
    for (size_t k = 0; k < std::size(halves); ++k) EXPECT_EQ(lanes(round_to_int(vfloat(halves[k])))[0], even[k]);
    EXPECT_TRUE(same_bits(lanes(floor(vfloat(-0.0f)))[0], -0.0f));
    EXPECT_EQ(lanes(floor(vfloat(-0.5f)))[0], -1.0f);
    EXPECT_EQ(lanes(floor(vfloat(-FLT_TRUE_MIN)))[0], -1.0f);
    EXPECT_EQ(lanes(floor(vfloat(-kInf)))[0], -kInf);
    EXPECT_EQ(lanes(to_float(vint(16777217)))[0], 16777216.0f);
    EXPECT_EQ(lanes(to_float(vint(INT32_MIN)))[0], -2147483648.0f);
}

TEST(Simd, LoadStoreGatherAndLaneIndex) {
    Rng rng(14);
    std::vector<float> table(1000);
    for (float& t : table) t = random_float(rng);
    for (int round = 0; round < kRounds; ++round) {
        Lanes<int32_t> index;
        for (int i = 0; i < kLanes; ++i) index[i] = int32_t(rng.uniform(0, int64_t(table.size()) - 1));
        const Lanes<float> g = lanes(gather(table.data(), load(index)));
        for (int i = 0; i < kLanes; ++i) ASSERT_TRUE(same_bits(g[i], table[size_t(index[i])]));
        const Lanes<float> a = random_floats(rng);
        const Lanes<float> back = lanes(load(a));
        for (int i = 0; i < kLanes; ++i) ASSERT_TRUE(same_bits(back[i], a[i]));
    }
    const Lanes<int32_t> lane = lanes(lane_index());
    for (int i = 0; i < kLanes; ++i) EXPECT_EQ(lane[i], i);
    const Lanes<float> splat = lanes(vfloat(-kNaN));
    const Lanes<int32_t> zero = lanes(vint());
    for (int i = 0; i < kLanes; ++i) {
        EXPECT_TRUE(same_bits(splat[i], -kNaN));
        EXPECT_EQ(zero[i], 0);
        EXPECT_EQ(lanes(vfloat())[i], 0.0f);
    }
}

TEST(Simd, GatherQuadsFetchesTheSameBitsAsFourGathers) {
    Rng rng(15);
    std::vector<float> table(4 * 257);  // 257 quads: an odd count, the last one gathered too
    for (float& t : table) t = random_float(rng);  // NaN payloads and signed zeros among them
    for (int round = 0; round < kRounds; ++round) {
        Lanes<int32_t> quad;
        for (int i = 0; i < kLanes; ++i) quad[i] = int32_t(rng.uniform(0, 256));
        if (round == 0) quad[0] = 256, quad[kLanes - 1] = 0;
        vfloat a, b, c, d;
        gather_quads(table.data(), load(quad), a, b, c, d);
        const Lanes<float> channel[4] = {lanes(a), lanes(b), lanes(c), lanes(d)};
        const vint first = load(quad) * vint(4);
        for (int k = 0; k < 4; ++k) {
            const Lanes<float> four = lanes(gather(table.data(), first + vint(k)));
            for (int i = 0; i < kLanes; ++i) {
                ASSERT_TRUE(same_bits(channel[k][i], table[4 * size_t(quad[i]) + size_t(k)]));
                ASSERT_TRUE(same_bits(channel[k][i], four[i]));
            }
        }
    }
}

TEST(Simd, InterleavedLoadsSplitTheThreeStreams) {
    std::vector<int32_t> values(3 * kLanes + 5);
    for (size_t i = 0; i < values.size(); ++i) values[i] = int32_t(i * 7919 + 13);
    for (int start = 0; start < 5; ++start) {  // unaligned
        vint a, b, c;
        load_interleaved3(values.data() + start, a, b, c);
        const Lanes<int32_t> x = lanes(a), y = lanes(b), z = lanes(c);
        for (int i = 0; i < kLanes; ++i) {
            ASSERT_EQ(x[i], values[size_t(start + 3 * i)]);
            ASSERT_EQ(y[i], values[size_t(start + 3 * i + 1)]);
            ASSERT_EQ(z[i], values[size_t(start + 3 * i + 2)]);
        }
    }
}

TEST(Simd, InterleavedStoresMergeTheThreeStreams) {
    Rng rng(21);
    for (int round = 0; round < kRounds; ++round) {
        const Lanes<float> a = random_floats(rng), b = random_floats(rng), c = random_floats(rng);
        std::vector<float> memory(3 * kLanes + 6, 7.0f);
        const int start = int(rng.uniform(0, 3));  // unaligned
        store_interleaved3(memory.data() + start, load(a), load(b), load(c));
        for (int i = 0; i < kLanes; ++i) {
            ASSERT_TRUE(same_bits(memory[size_t(start + 3 * i)], a[i]));
            ASSERT_TRUE(same_bits(memory[size_t(start + 3 * i + 1)], b[i]));
            ASSERT_TRUE(same_bits(memory[size_t(start + 3 * i + 2)], c[i]));
        }
        for (size_t j = 0; j < memory.size(); ++j)  // nothing outside the 3 * kLanes values
            if (j < size_t(start) || j >= size_t(start + 3 * kLanes)) ASSERT_EQ(memory[j], 7.0f);
    }
}

TEST(Simd, CompressMovesTheSelectedLanesDownInOrder) {
    Rng rng(22);
    for (int round = 0; round < kRounds; ++round) {
        const uint32_t pattern = uint32_t(rng.bits()) & all_bits();
        const Lanes<float> a = random_floats(rng);
        const Lanes<int32_t> n = random_ints(rng);
        const Lanes<float> packed = lanes(compress(mask_of(pattern), load(a)));
        const Lanes<int32_t> packed_n = lanes(compress(mask_of(pattern), load(n)));
        int k = 0;
        for (int i = 0; i < kLanes; ++i)
            if ((pattern >> i) & 1u) {
                ASSERT_TRUE(same_bits(packed[k], a[i]));
                ASSERT_EQ(packed_n[k], n[i]);
                ++k;
            }
        for (; k < kLanes; ++k) {
            ASSERT_TRUE(same_bits(packed[k], 0.0f));
            ASSERT_EQ(packed_n[k], 0);
        }
        std::vector<float> memory(kLanes + 3);
        load(a).store_unaligned(memory.data() + 3);
        for (int i = 0; i < kLanes; ++i) ASSERT_TRUE(same_bits(memory[size_t(3 + i)], a[i]));
    }
}

TEST(Simd, MaskedStoresWriteOnlyTheSelectedLanes) {
    Rng rng(15);
    for (int round = 0; round < kRounds; ++round) {
        const uint32_t pattern = uint32_t(rng.bits()) & all_bits();
        const Lanes<float> a = random_floats(rng), before = random_floats(rng);
        const Lanes<int32_t> n = random_ints(rng), before_n = random_ints(rng);
        Lanes<float> memory = before;
        Lanes<uint32_t> ints;
        for (int i = 0; i < kLanes; ++i) ints[i] = uint32_t(before_n[i]);
        store_masked(memory.v, mask_of(pattern), load(a));
        store_masked(ints.v, mask_of(pattern), load(n));
        for (int i = 0; i < kLanes; ++i) {
            const bool on = (pattern >> i) & 1u;
            ASSERT_TRUE(same_bits(memory[i], on ? a[i] : before[i]));
            ASSERT_EQ(ints[i], uint32_t(on ? n[i] : before_n[i]));
        }
    }
}

// Lane i of a stamp is pixel (i % kStampW, i / kStampW) of a kStampW x kStampH stamp.
TEST(Simd, StampLanesAreRowMajorInTheStamp) {
    static_assert(kStampW * kStampH == kLanes);
    const Lanes<int32_t> x = lanes(stamp_x()), y = lanes(stamp_y());
    for (int i = 0; i < kLanes; ++i) {
        EXPECT_EQ(x[i], i % kStampW);
        EXPECT_EQ(y[i], i / kStampW);
    }
    if constexpr (kLanes == 16) {
        EXPECT_EQ(kStampW, 4);
    }
    if constexpr (kLanes == 8) {
        EXPECT_EQ(kStampH, 2);
    }
}

// kStampH stamps side by side (kLanes values each, stamp s covering pixels s * kStampW ..)
// to `rows` rows of kLanes values at dst + r * stride; nothing else is written.
TEST(Simd, StoreStampRowsTransposesStampsToRows) {
    Rng rng(16);
    struct alignas(64) Stamps {
        uint32_t v[kLanes * kStampH];
    } stamps;
    for (uint32_t& v : stamps.v) v = uint32_t(rng.bits());
    for (size_t stride : {size_t(kLanes), size_t(kLanes) + 3, size_t(4 * kLanes)})
        for (int rows = 1; rows <= kStampH; ++rows) {
            const uint32_t sentinel = 0xDEADBEEFu;
            std::vector<uint32_t> dst(stride * kStampH + 8, sentinel);
            store_stamp_rows(stamps.v, dst.data() + 1, stride, rows);  // unaligned destination
            for (size_t k = 0; k < dst.size(); ++k) {
                const long p = long(k) - 1;
                const int r = int(p / long(stride)), x = int(p % long(stride));
                uint32_t expected = sentinel;
                if (p >= 0 && r < rows && x < kLanes) {
                    const int s = x / kStampW, lane = r * kStampW + x % kStampW;
                    expected = stamps.v[s * kLanes + lane];
                }
                ASSERT_EQ(dst[k], expected) << "stride " << stride << " rows " << rows << " at " << k;
            }
        }
}

// stream_copy: the n values, whatever the destination's alignment, and nothing around them.
TEST(Simd, StreamCopyCopiesExactlyTheValues) {
    Rng rng(17);
    AlignedVector<uint32_t> src(300), dst(300 + 64);
    for (uint32_t& v : src) v = uint32_t(rng.bits());
    for (size_t offset = 0; offset < 20; ++offset)
        for (size_t n = 0; n <= 3 * 16 + 5; ++n) {
            std::fill(dst.begin(), dst.end(), 0xCDCDCDCDu);
            stream_copy(dst.data() + offset, src.data() + (n % 7), n);
            stream_fence();
            for (size_t k = 0; k < dst.size(); ++k) {
                const bool in = k >= offset && k < offset + n;
                ASSERT_EQ(dst[k], in ? src[k - offset + n % 7] : 0xCDCDCDCDu) << "offset " << offset << " n " << n;
            }
        }
}

}  // namespace
}  // namespace tessera::simd
