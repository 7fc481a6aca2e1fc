// 8-bit sRGB encoding of linear values by table, equal for every float to the definition
//     e = uint8(linear_to_srgb(c) * 255 + 0.5)            (core/color_space.h)
// without a power per value: the dominant per-pixel cost of writing a PNG frame otherwise.
//
// The definition is monotonic in c (checked for every float in [0, 1]; the test checks the
// table's edges), so level k begins at a threshold t[k], the smallest float that encodes to
// k, found once by bisection over the floats' bit patterns. Floats in [2^-14, 1) fall into
// buckets by exponent and the top 7 mantissa bits (1792 buckets). The sRGB curve rises by at
// most 0.9 of a level across any bucket (steepest: 12.92 * 255 per unit near 0, 1.055 / 2.4
// * 255 per unit near 1 against a bucket 1/128 wide), so a bucket holds at most one
// threshold: the level is the bucket's first level plus one comparison. Below 2^-14 every
// value encodes to 0 (the first level starts at 1.5e-4), at 1 and above to 255, NaN to 0.
#pragma once
#include <glm/vec4.hpp>

#include <cstddef>
#include <cstdint>

namespace tessera::output {

// The definition above, one value at a time (the reference the table is checked against).
uint8_t srgb8_reference(float linear);
// Alpha is linear coverage: clamped to [0, 1] (NaN gives 0) and quantised with rounding.
uint8_t alpha8(float alpha);

// The table form of srgb8_reference.
uint8_t srgb8(float linear);

// n pixels of linear RGBA to 8-bit RGBA (RGB sRGB-encoded, alpha linear), 4 n bytes: srgb8()
// and alpha8() value by value, simd::kLanes values at a time (the two table reads one
// gather). Returns false when some value is NaN or infinite (encoded as those functions say),
// so that the caller need not read the frame again to find out.
bool encode_srgb8(const glm::vec4* pixels, size_t n, uint8_t* out);

}  // namespace tessera::output
