// Scalar maths written so that GCC vectorises loops that call it (std::floor and std::sin stay
// scalar library calls under GCC 12 without -ffast-math). Used by the noise kernels and by the
// 16-sine noise; each function is its own scalar reference and is tested against <cmath>.
#pragma once
#include <cstdint>

namespace tessera::procedural {

// floor(x) as an integer, for |x| < 2^31: truncate, then step down when truncation rounded up.
inline int32_t floor_int(float x) {
    const int32_t i = int32_t(x);
    return i - int32_t(float(i) > x);
}

// sin(x) and cos(x) together, absolute error below 1e-6 for |x| <= 1e4 (tested). Cody-Waite
// reduction by pi/2 in three parts (the first two exact in float), then the Cephes minimax
// polynomials on [-pi/4, pi/4] and a quadrant swap, all branch-free.
inline void sincos_approx(float x, float& sine, float& cosine) {
    const int32_t q = floor_int(x * 0.636619772367581343f + 0.5f);  // nearest multiple of pi/2
    const float fq = float(q);
    float r = x - fq * 1.5703125f;
    r -= fq * 4.837512969970703125e-4f;
    r -= fq * 7.54978995489188216e-8f;
    const float z = r * r;
    const float s =
        r + r * z * (-1.6666654611e-1f + z * (8.3321608736e-3f + z * -1.9515295891e-4f));
    const float c = 1.0f - 0.5f * z +
                    z * z * (4.166664568298827e-2f + z * (-1.388731625493765e-3f +
                                                          z * 2.443315711809948e-5f));
    const bool swap = (q & 1) != 0;
    const float sin_r = swap ? c : s;
    const float cos_r = swap ? s : c;
    sine = (q & 2) ? -sin_r : sin_r;
    cosine = ((q + 1) & 2) ? -cos_r : cos_r;
}

}  // namespace tessera::procedural
