#include "raster/output/srgb8.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "raster/core/color_space.h"
#include "raster/simd/simd.h"

namespace tessera::output {
namespace {

constexpr uint32_t kLowBits = (127u - 14u) << 23;  // 2^-14
constexpr uint32_t kOneBits = 127u << 23;          // 1.0
constexpr uint32_t kFirstBucket = kLowBits >> 16;
constexpr uint32_t kBuckets = (kOneBits >> 16) - kFirstBucket;  // 14 exponents x 128

struct Table {
    std::array<int32_t, kBuckets> first_level{};
    // The same per bucket in one word for the lanes' single gather: first level << 17 | the
    // low 16 bits of the next level's threshold when that threshold lies in the bucket (the
    // bucket's values share their high 16 bits), else 2^16, which no value's low bits reach.
    std::array<int32_t, kBuckets> packed{};
    // threshold[k]: the smallest float encoding to level k (k = 1..255); threshold[256] = inf.
    std::array<float, 257> threshold{};

    Table() {
        threshold[0] = 0.0f;
        for (uint32_t k = 1; k < 256; ++k) {
            // Bisection over bit patterns of [0, 1]: positive floats order as their bits.
            uint32_t lo = 0, hi = kOneBits;  // srgb8(lo) < k <= srgb8(hi)
            while (hi - lo > 1) {
                const uint32_t mid = lo + (hi - lo) / 2;
                (srgb8_reference(std::bit_cast<float>(mid)) >= k ? hi : lo) = mid;
            }
            threshold[k] = std::bit_cast<float>(hi);
        }
        threshold[256] = std::numeric_limits<float>::infinity();
        for (uint32_t b = 0; b < kBuckets; ++b) {
            const uint32_t start = (kFirstBucket + b) << 16, last = start + 0xFFFFu;
            const uint32_t level = srgb8_reference(std::bit_cast<float>(start));
            first_level[b] = int32_t(level);
            // The one-comparison rule needs at most one threshold inside a bucket.
            if (srgb8_reference(std::bit_cast<float>(last)) > level + 1)
                throw std::logic_error("srgb8: a bucket spans more than two levels");
            const uint32_t next = std::bit_cast<uint32_t>(threshold[level + 1]);
            packed[b] = int32_t(level << 17 | ((next >> 16) == (start >> 16) ? (next & 0xFFFFu) : 0x10000u));
        }
        if (srgb8_reference(std::bit_cast<float>(kLowBits - 1)) != 0)
            throw std::logic_error("srgb8: values below 2^-14 must encode to 0");
    }
};

const Table& table() {
    static const Table t;
    return t;
}

// Branch-free so that the pixel loop vectorises (gathers for the two lookups).
inline uint8_t lookup(const Table& t, float c) {
    const float low = std::bit_cast<float>(kLowBits);
    const float below_one = std::bit_cast<float>(kOneBits - 1);
    const float inside = c >= low ? (c < 1.0f ? c : below_one) : low;  // NaN -> low
    const uint32_t bucket = (std::bit_cast<uint32_t>(inside) >> 16) - kFirstBucket;
    const int32_t first = t.first_level[bucket];
    const int32_t level = first + int32_t(inside >= t.threshold[size_t(first) + 1]);
    return uint8_t(c >= 1.0f ? 255 : (c >= low ? level : 0));
}

}  // namespace

uint8_t srgb8_reference(float linear) { return uint8_t(linear_to_srgb(linear) * 255.0f + 0.5f); }

uint8_t alpha8(float alpha) {
    const float a = alpha > 0.0f ? std::min(alpha, 1.0f) : 0.0f;  // NaN -> 0
    return uint8_t(a * 255.0f + 0.5f);
}

uint8_t srgb8(float linear) { return lookup(table(), linear); }

bool encode_srgb8(const glm::vec4* pixels, size_t n, uint8_t* out) {
    const Table& t = table();
    const float* in = &pixels[0].x;
    const size_t values = 4 * n;
    size_t i = 0;
    bool finite = true;
    if constexpr (simd::kLanes % 4 == 0) {
        // kLanes values (kLanes / 4 pixels) per step: lookup() and alpha8() lane for lane, the
        // two table reads as one gather of `packed`. Alpha lanes (3, 7, ...) are computed as
        // colour too and selected, so the loop has no branch on the channel.
        using simd::vfloat;
        using simd::vint;
        using simd::vmask;
        const vfloat low(std::bit_cast<float>(kLowBits)), one(1.0f), below_one(std::bit_cast<float>(kOneBits - 1));
        const vfloat zero(0.0f);
        const vmask alpha_lane = (simd::lane_index() & vint(3)) == vint(3);
        const vint exponent_bits(0x7F800000);
        vmask non_finite(false);
        for (; i + simd::kLanes <= values; i += simd::kLanes) {
            const vfloat c = vfloat::load_unaligned(in + i);
            const vmask from_low = low <= c, from_one = one <= c;  // NaN: neither
            const vfloat inside = simd::select(from_low, simd::select(from_one, below_one, c), low);
            const vint b = simd::bits_of(inside);
            const vint entry = simd::bits_of(simd::gather(reinterpret_cast<const float*>(t.packed.data()),
                                                          (b >> vint(16)) - vint(int32_t(kFirstBucket))));
            const vint level = (entry >> vint(17)) +
                               simd::select((b & vint(0xFFFF)) >= (entry & vint(0x1FFFF)), vint(1), vint(0));
            const vint colour = simd::select(from_one, vint(255), simd::select(from_low, level, vint(0)));
            const vfloat a = simd::select(zero < c, simd::select(one < c, one, c), zero);
            const vint alpha = simd::round_to_int(simd::floor(a * vfloat(255.0f) + vfloat(0.5f)));
            simd::store_low_bytes(out + i, simd::select(alpha_lane, alpha, colour));
            non_finite = non_finite | ((simd::bits_of(c) & exponent_bits) == exponent_bits);
        }
        finite = !simd::any(non_finite);
    }
    for (; i < values; ++i) {
        const float c = in[i];
        out[i] = (i & 3) == 3 ? alpha8(c) : lookup(t, c);
        finite &= std::isfinite(c);
    }
    return finite;
}

}  // namespace tessera::output
