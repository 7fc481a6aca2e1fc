// Deterministic integer hashing for procedural generators: the same (seed, coordinates) give
// the same value on every machine and thread count, with no shared random-number state.
#pragma once
#include <cstdint>

namespace tessera::procedural {

// A 32-bit avalanche mix (the "lowbias32" finaliser: every input bit flips each output bit
// with probability close to 1/2), cheap enough to vectorise.
constexpr uint32_t mix32(uint32_t x) {
    x ^= x >> 16;
    x *= 0x7feb352dU;
    x ^= x >> 15;
    x *= 0x846ca68bU;
    x ^= x >> 16;
    return x;
}

// Hash of a seed and up to three integer lattice coordinates.
constexpr uint32_t hash(uint32_t seed, int32_t x, int32_t y = 0, int32_t z = 0) {
    uint32_t h = mix32(seed ^ 0x9e3779b9U);
    h = mix32(h ^ uint32_t(x));
    h = mix32(h ^ (uint32_t(y) * 0x85ebca6bU));
    h = mix32(h ^ (uint32_t(z) * 0xc2b2ae35U));
    return h;
}

// Uniform float in [0, 1) from the top 24 bits of a hash.
constexpr float unit_float(uint32_t h) { return float(h >> 8) * (1.0f / 16777216.0f); }

// A counter-based generator: sample i of stream `seed` is independent of how many threads
// drew samples before it.
class SplitMix64 {
public:
    explicit constexpr SplitMix64(uint64_t seed) : state_(seed) {}
    constexpr uint64_t next() {
        uint64_t z = (state_ += 0x9e3779b97f4a7c15ULL);
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
        return z ^ (z >> 31);
    }
    constexpr float next_float() { return float(next() >> 40) * (1.0f / 16777216.0f); }

private:
    uint64_t state_;
};

}  // namespace tessera::procedural
