// Flush-to-zero / denormals-are-zero for the duration of a scope, on the calling thread.
//
// Why: in reaction-diffusion the B concentration outside the pattern decays geometrically
// (factor 1 - (F + k) dt per step), so large decayed regions sink into the float denormal
// range, where x86 cores take microcode assists on every operation and a SIMD step slows
// down many times over. Flushing them to zero changes nothing visible (they are < 1e-38).
//
// Why per scope rather than once in main(): MXCSR is per thread, and oneTBB workers take the
// FP mode of whichever thread created their arena. Setting it in every parallel chunk makes the
// mode - and so the bits of the result - identical on every thread whatever the caller did,
// which the thread-count determinism of the generators depends on. The previous mode is
// restored, so the caller's own arithmetic is untouched.
#pragma once
#if defined(__SSE2__)
#include <immintrin.h>
#endif

namespace tessera::procedural {

class FlushDenormals {
public:
#if defined(__SSE2__)
    FlushDenormals() : saved_(_mm_getcsr()) { _mm_setcsr(saved_ | kFlushToZero | kDenormalsAreZero); }
    ~FlushDenormals() { _mm_setcsr(saved_); }
#endif
    FlushDenormals(const FlushDenormals&) = delete;
    FlushDenormals& operator=(const FlushDenormals&) = delete;

private:
#if defined(__SSE2__)
    static constexpr unsigned kFlushToZero = 0x8000;      // MXCSR bit 15
    static constexpr unsigned kDenormalsAreZero = 0x0040; // MXCSR bit 6
    unsigned saved_;
#endif
};

}  // namespace tessera::procedural
