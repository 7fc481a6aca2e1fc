#include "raster/output/adler32.h"

#include <algorithm>

namespace tessera::output {
namespace {

constexpr uint32_t kBase = 65521;
constexpr size_t kBlock = 32;
// The most blocks before a reduction: 5552 bytes (zlib's NMAX) keep s2 below 2^32.
constexpr size_t kBlocksPerRound = 5552 / kBlock;

}  // namespace

uint32_t adler32_update(uint32_t adler, const uint8_t* data, size_t n) {
    uint64_t s1 = adler & 0xFFFFu, s2 = adler >> 16;
    while (n >= kBlock) {
        const size_t blocks = std::min(n / kBlock, kBlocksPerRound);
        // Lane i: the sum of byte i of each block (sum), and the sum over blocks of the sum
        // before it (prior), so that byte i of block j counts (blocks - 1 - j) times in prior.
        uint32_t sum[kBlock] = {}, prior[kBlock] = {};
        for (size_t b = 0; b < blocks; ++b) {
            const uint8_t* p = data + b * kBlock;
            for (size_t i = 0; i < kBlock; ++i) {
                prior[i] += sum[i];
                sum[i] += p[i];
            }
        }
        // Byte i of block j is followed by (blocks - 1 - j) * 32 + (32 - i) bytes, s1 before
        // the round by all blocks * 32.
        uint64_t bytes = 0, weighted = 0;
        for (size_t i = 0; i < kBlock; ++i) {
            bytes += sum[i];
            weighted += uint64_t(kBlock) * prior[i] + uint64_t(kBlock - i) * sum[i];
        }
        s2 = (s2 + uint64_t(blocks * kBlock) * s1 + weighted) % kBase;
        s1 = (s1 + bytes) % kBase;
        data += blocks * kBlock;
        n -= blocks * kBlock;
    }
    for (size_t i = 0; i < n; ++i) {
        s1 += data[i];
        s2 += s1;
    }
    return uint32_t((s2 % kBase) << 16 | (s1 % kBase));
}

}  // namespace tessera::output
