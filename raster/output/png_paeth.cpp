#include "raster/output/png_paeth.h"

#include <algorithm>
#include <cstdlib>

#if defined(__AVX512BW__) || defined(__AVX2__)
#include <immintrin.h>
#endif

namespace tessera::output {
namespace {

uint8_t paeth_predictor(int a, int b, int c) {
    const int p = a + b - c;
    const int pa = std::abs(p - a), pb = std::abs(p - b), pc = std::abs(p - c);
    return uint8_t(pa <= pb && pa <= pc ? a : (pb <= pc ? b : c));
}

#if defined(__AVX512BW__)
constexpr size_t kStep = 64;

// kStep residuals from byte i (i >= bpp) on: the header's byte form, masks for the choices.
inline void paeth_step(const uint8_t* row, const uint8_t* up, size_t i, size_t bpp, uint8_t* out) {
    const __m512i x = _mm512_loadu_si512(row + i), a = _mm512_loadu_si512(row + i - bpp);
    const __m512i b = _mm512_loadu_si512(up + i), c = _mm512_loadu_si512(up + i - bpp);
    const __m512i pa = _mm512_sub_epi8(_mm512_max_epu8(b, c), _mm512_min_epu8(b, c));
    const __m512i pb = _mm512_sub_epi8(_mm512_max_epu8(a, c), _mm512_min_epu8(a, c));
    const __mmask64 same_sign = ~(_mm512_cmpge_epu8_mask(b, c) ^ _mm512_cmpge_epu8_mask(a, c));
    const __m512i pc = _mm512_mask_blend_epi8(same_sign, _mm512_sub_epi8(_mm512_max_epu8(pa, pb), _mm512_min_epu8(pa, pb)),
                                              _mm512_adds_epu8(pa, pb));
    const __mmask64 take_a = _mm512_cmple_epu8_mask(pa, pb) & _mm512_cmple_epu8_mask(pa, pc);
    const __mmask64 take_b = _mm512_cmple_epu8_mask(pb, pc);
    const __m512i predicted = _mm512_mask_blend_epi8(take_a, _mm512_mask_blend_epi8(take_b, c, b), a);
    _mm512_storeu_si512(out + i, _mm512_sub_epi8(x, predicted));
}
#elif defined(__AVX2__)
constexpr size_t kStep = 32;

inline __m256i absolute_difference(__m256i x, __m256i y) {
    return _mm256_sub_epi8(_mm256_max_epu8(x, y), _mm256_min_epu8(x, y));
}
// All ones in the bytes where x <= y (unsigned): AVX2 compares bytes only as signed.
inline __m256i at_most(__m256i x, __m256i y) { return _mm256_cmpeq_epi8(_mm256_min_epu8(x, y), x); }

inline void paeth_step(const uint8_t* row, const uint8_t* up, size_t i, size_t bpp, uint8_t* out) {
    const auto load = [](const uint8_t* p) { return _mm256_loadu_si256(reinterpret_cast<const __m256i*>(p)); };
    const __m256i x = load(row + i), a = load(row + i - bpp), b = load(up + i), c = load(up + i - bpp);
    const __m256i pa = absolute_difference(b, c), pb = absolute_difference(a, c);
    const __m256i other_sign = _mm256_xor_si256(at_most(c, b), at_most(c, a));
    const __m256i pc = _mm256_blendv_epi8(_mm256_adds_epu8(pa, pb), absolute_difference(pa, pb), other_sign);
    const __m256i take_a = _mm256_and_si256(at_most(pa, pb), at_most(pa, pc));
    const __m256i predicted = _mm256_blendv_epi8(_mm256_blendv_epi8(c, b, at_most(pb, pc)), a, take_a);
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(out + i), _mm256_sub_epi8(x, predicted));
}
#endif

}  // namespace

void paeth_residuals_reference(const uint8_t* row, const uint8_t* up, size_t n, size_t bpp, uint8_t* out) {
    for (size_t i = 0; i < n; ++i) {
        const bool left = i >= bpp;
        out[i] = uint8_t(row[i] - paeth_predictor(left ? row[i - bpp] : 0, up[i], left ? up[i - bpp] : 0));
    }
}

void paeth_residuals(const uint8_t* __restrict row, const uint8_t* __restrict up, size_t n, size_t bpp,
                     uint8_t* __restrict out) {
    // The first pixel has no left neighbour (a = c = 0: the predictor is b).
    const size_t first = std::min(bpp, n);
    for (size_t i = 0; i < first; ++i) out[i] = uint8_t(row[i] - up[i]);
    size_t i = first;
#if defined(__AVX512BW__) || defined(__AVX2__)
    for (; i + kStep <= n; i += kStep) paeth_step(row, up, i, bpp, out);
#endif
    // The rest (and every byte without a vector unit) in the scalar predictor's branch-free
    // form with pa, pb, pc as in the header.
    for (; i < n; ++i) {
        const int a = row[i - bpp], b = up[i], c = up[i - bpp];
        const int pa = std::abs(b - c), pb = std::abs(a - c), pc = std::abs(a + b - 2 * c);
        out[i] = uint8_t(row[i] - (pa <= pb && pa <= pc ? a : (pb <= pc ? b : c)));
    }
}

}  // namespace tessera::output
