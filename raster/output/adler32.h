// Adler-32 (RFC 1950 section 8.2): s1 = 1 + the sum of the bytes, s2 = the sum of the s1 after
// each byte, both modulo 65521, checksum s2 * 65536 + s1. The same value as zlib's adler32(),
// computed 32 bytes per step: over a block of 32 bytes starting from (s1, s2),
//     s2 += 32 s1 + sum (32 - i) x_i,   s1 += sum x_i,
// so per-lane sums of the bytes and of those sums (prefix sums, a multiply-free form that the
// compiler vectorises) give both after any number of blocks, reduced modulo 65521 before
// 32-bit lanes could overflow (zlib's NMAX bound, 5552 bytes).
#pragma once
#include <cstddef>
#include <cstdint>

namespace tessera::output {

// Continues the checksum `adler` (1 for an empty input) over n bytes.
uint32_t adler32_update(uint32_t adler, const uint8_t* data, size_t n);

}  // namespace tessera::output
