#include "raster/output/srgb8.h"

#include <algorithm>
#include <array>
#include <bit>
#include <limits>
#include <stdexcept>

#include "raster/core/color_space.h"

namespace tessera::output {
namespace {

constexpr uint32_t kLowBits = (127u - 14u) << 23;  // 2^-14
constexpr uint32_t kOneBits = 127u << 23;          // 1.0
constexpr uint32_t kFirstBucket = kLowBits >> 16;
constexpr uint32_t kBuckets = (kOneBits >> 16) - kFirstBucket;  // 14 exponents x 128

struct Table {
    std::array<int32_t, kBuckets> first_level{};
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

void encode_srgb8(const glm::vec4* pixels, size_t n, uint8_t* out) {
    const Table& t = table();
    const float* in = &pixels[0].x;
    for (size_t i = 0; i < 4 * n; ++i) {
        const float c = in[i];
        // Lanes 3, 7, ... are alpha: computed for every lane and selected, so the loop has no
        // branch on the channel and stays one vector loop.
        const uint8_t colour = lookup(t, c);
        const float a = c > 0.0f ? std::min(c, 1.0f) : 0.0f;
        out[i] = (i & 3) == 3 ? uint8_t(a * 255.0f + 0.5f) : colour;
    }
}

}  // namespace tessera::output
