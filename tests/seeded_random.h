// Deterministic random numbers for property tests: fixed seeds, the same sequence on every
// machine, compiler and build (SplitMix64, no std:: distribution whose output is unspecified).
#pragma once
#include <cstdint>

#include "procedural/hash.h"

namespace tessera::test {

class Rng {
public:
    explicit Rng(uint64_t seed) : generator_(seed) {}
    uint64_t bits() { return generator_.next(); }
    // Uniform in [lo, hi] (inclusive; the modulo bias is irrelevant here).
    int64_t uniform(int64_t lo, int64_t hi) { return lo + int64_t(bits() % uint64_t(hi - lo + 1)); }
    // Uniform in [0, 1).
    float unit() { return generator_.next_float(); }
    bool chance(int percent) { return uniform(0, 99) < percent; }

private:
    procedural::SplitMix64 generator_;
};

}  // namespace tessera::test
