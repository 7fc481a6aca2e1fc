// AVX-512 back end of simd.h: 16 float / int32 lanes, masks in k registers.
#pragma once
#include <immintrin.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>

// GCC 12's plain min/max/cvt/sqrt/gather/srav intrinsics pass an _mm512_undefined_ps() operand to
// their masked builtins, which -Wuninitialized reports wherever they are inlined; the masked
// forms with an all-ones mask and an explicit pass-through compile to the same instructions.

namespace tessera::simd {

inline constexpr __mmask16 kAllLanes = 0xFFFF;

inline constexpr int kLanes = 16;

struct vmask {
    __mmask16 m = 0;
    vmask() = default;
    explicit vmask(__mmask16 k) : m(k) {}
    explicit vmask(bool b) : m(b ? 0xFFFF : 0) {}
};
inline vmask operator&(vmask a, vmask b) { return vmask(__mmask16(a.m & b.m)); }
inline vmask operator|(vmask a, vmask b) { return vmask(__mmask16(a.m | b.m)); }
inline vmask andnot(vmask a, vmask b) { return vmask(__mmask16(~a.m & b.m)); }
inline bool any(vmask a) { return a.m != 0; }
inline bool all(vmask a) { return a.m == 0xFFFF; }
inline uint32_t bits(vmask a) { return a.m; }

struct vint {
    __m512i v;
    vint() : v(_mm512_setzero_si512()) {}
    vint(__m512i x) : v(x) {}
    vint(int32_t s) : v(_mm512_set1_epi32(s)) {}
    static vint load(const int32_t* p) { return _mm512_load_si512(p); }
    static vint load_unaligned(const int32_t* p) { return _mm512_loadu_si512(p); }
    void store(int32_t* p) const { _mm512_store_si512(p, v); }
    void store_unaligned(int32_t* p) const { _mm512_storeu_si512(p, v); }
};
inline vint operator+(vint a, vint b) { return _mm512_add_epi32(a.v, b.v); }
inline vint operator-(vint a, vint b) { return _mm512_sub_epi32(a.v, b.v); }
inline vint operator*(vint a, vint b) { return _mm512_mullo_epi32(a.v, b.v); }
inline vint operator&(vint a, vint b) { return _mm512_and_si512(a.v, b.v); }
inline vint operator|(vint a, vint b) { return _mm512_or_si512(a.v, b.v); }
inline vint operator^(vint a, vint b) { return _mm512_xor_si512(a.v, b.v); }
inline vint min(vint a, vint b) { return _mm512_mask_min_epi32(a.v, kAllLanes, a.v, b.v); }
inline vint max(vint a, vint b) { return _mm512_mask_max_epi32(a.v, kAllLanes, a.v, b.v); }
inline vint operator>>(vint a, vint s) { return _mm512_mask_srav_epi32(a.v, kAllLanes, a.v, s.v); }
// Shifts by a constant count in [0, 31]: left, and right filling with zeros (logical).
template <int N>
inline vint shift_left(vint a) { return _mm512_mask_slli_epi32(a.v, kAllLanes, a.v, N); }
template <int N>
inline vint shift_right_logical(vint a) { return _mm512_mask_srli_epi32(a.v, kAllLanes, a.v, N); }
inline int32_t first_lane(vint a) { return _mm512_cvtsi512_si32(a.v); }
// Lane i (0 <= i < kLanes), without a round trip through memory.
inline int32_t lane(vint a, int i) { return _mm512_cvtsi512_si32(_mm512_permutexvar_epi32(_mm512_set1_epi32(i), a.v)); }
inline vmask operator>=(vint a, vint b) { return vmask(_mm512_cmpge_epi32_mask(a.v, b.v)); }
inline vmask operator<(vint a, vint b) { return vmask(_mm512_cmplt_epi32_mask(a.v, b.v)); }
inline vmask operator==(vint a, vint b) { return vmask(_mm512_cmpeq_epi32_mask(a.v, b.v)); }
inline vint select(vmask m, vint a, vint b) { return _mm512_mask_blend_epi32(m.m, b.v, a.v); }
inline vint lane_index() {
    return _mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
}

struct vfloat {
    __m512 v;
    vfloat() : v(_mm512_setzero_ps()) {}
    vfloat(__m512 x) : v(x) {}
    vfloat(float s) : v(_mm512_set1_ps(s)) {}
    static vfloat load(const float* p) { return _mm512_load_ps(p); }
    static vfloat load_unaligned(const float* p) { return _mm512_loadu_ps(p); }
    void store_unaligned(float* p) const { _mm512_storeu_ps(p, v); }
    void store(float* p) const { _mm512_store_ps(p, v); }
};
inline vfloat operator+(vfloat a, vfloat b) { return _mm512_add_ps(a.v, b.v); }
inline vfloat operator-(vfloat a, vfloat b) { return _mm512_sub_ps(a.v, b.v); }
inline vfloat operator*(vfloat a, vfloat b) { return _mm512_mul_ps(a.v, b.v); }
inline vfloat operator/(vfloat a, vfloat b) { return _mm512_div_ps(a.v, b.v); }
inline vfloat fma(vfloat a, vfloat b, vfloat c) { return _mm512_fmadd_ps(a.v, b.v, c.v); }
// min/max return the second operand when either is NaN, like the scalar `a < b ? a : b`.
inline vfloat min(vfloat a, vfloat b) { return _mm512_mask_min_ps(a.v, kAllLanes, a.v, b.v); }
inline vfloat max(vfloat a, vfloat b) { return _mm512_mask_max_ps(a.v, kAllLanes, a.v, b.v); }
inline vmask operator<(vfloat a, vfloat b) { return vmask(_mm512_cmp_ps_mask(a.v, b.v, _CMP_LT_OQ)); }
inline vmask operator<=(vfloat a, vfloat b) { return vmask(_mm512_cmp_ps_mask(a.v, b.v, _CMP_LE_OQ)); }
inline vfloat select(vmask m, vfloat a, vfloat b) { return _mm512_mask_blend_ps(m.m, b.v, a.v); }
inline vfloat to_float(vint a) { return _mm512_mask_cvtepi32_ps(_mm512_setzero_ps(), kAllLanes, a.v); }
inline vfloat sqrt(vfloat a) { return _mm512_mask_sqrt_ps(a.v, kAllLanes, a.v); }
inline vfloat floor(vfloat a) {
    return _mm512_mask_roundscale_ps(a.v, kAllLanes, a.v, _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC);
}
inline vint round_to_int(vfloat a) {  // nearest even
    return _mm512_mask_cvtps_epi32(_mm512_setzero_si512(), kAllLanes, a.v);
}
inline vfloat gather(const float* base, vint index) {
    return _mm512_mask_i32gather_ps(_mm512_setzero_ps(), kAllLanes, index.v, base, 4);
}

// Lane i of a, b, c, d = base[4 q_i .. 4 q_i + 3] (simd.h). Four gathers of eight 64-bit
// pairs ((a, b) and (c, d) of lanes 0-7 and 8-15) and a two-source permute per channel: half
// the elements of four 16-lane float gathers, whose cost grows with the elements fetched.
inline void gather_quads(const float* base, vint quad, vfloat& a, vfloat& b, vfloat& c, vfloat& d) {
    const __m512i pair = _mm512_add_epi32(quad.v, quad.v);  // in 8-byte units: exact below 2^30 quads
    const __m256i low = _mm512_maskz_extracti64x4_epi64(0xF, pair, 0);
    const __m256i high = _mm512_maskz_extracti64x4_epi64(0xF, pair, 1);
    const __m512d none = _mm512_setzero_pd();
    const __m512 ab0 = _mm512_castpd_ps(_mm512_mask_i32gather_pd(none, 0xFF, low, base, 8));
    const __m512 ab1 = _mm512_castpd_ps(_mm512_mask_i32gather_pd(none, 0xFF, high, base, 8));
    const __m512 cd0 = _mm512_castpd_ps(_mm512_mask_i32gather_pd(none, 0xFF, low, base + 2, 8));
    const __m512 cd1 = _mm512_castpd_ps(_mm512_mask_i32gather_pd(none, 0xFF, high, base + 2, 8));
    const __m512i even = _mm512_setr_epi32(0, 2, 4, 6, 8, 10, 12, 14, 16, 18, 20, 22, 24, 26, 28, 30);
    const __m512i odd = _mm512_add_epi32(even, _mm512_set1_epi32(1));
    a.v = _mm512_permutex2var_ps(ab0, even, ab1);
    b.v = _mm512_permutex2var_ps(ab0, odd, ab1);
    c.v = _mm512_permutex2var_ps(cd0, even, cd1);
    d.v = _mm512_permutex2var_ps(cd0, odd, cd1);
}

// The bits of each lane as the other type (no conversion).
inline vint bits_of(vfloat a) { return _mm512_castps_si512(a.v); }
inline vfloat float_of_bits(vint a) { return _mm512_castsi512_ps(a.v); }
// The low byte of each lane to p[0 .. kLanes) (unaligned).
inline void store_low_bytes(uint8_t* p, vint a) { _mm_storeu_si128(reinterpret_cast<__m128i*>(p), _mm512_cvtepi32_epi8(a.v)); }

// The three streams of 3 * kLanes consecutive values (unaligned): a[i] = p[3i], b[i] = p[3i + 1],
// c[i] = p[3i + 2]. Two two-source permutes per stream: the values below p + 32, then the rest.
inline void load_interleaved3(const int32_t* p, vint& a, vint& b, vint& c) {
    const __m512i x = _mm512_loadu_si512(p), y = _mm512_loadu_si512(p + 16), z = _mm512_loadu_si512(p + 32);
    const __m512i lane = _mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
    vint* out[3] = {&a, &b, &c};
    for (int k = 0; k < 3; ++k) {
        const __m512i from = _mm512_add_epi32(_mm512_mullo_epi32(lane, _mm512_set1_epi32(3)), _mm512_set1_epi32(k));
        const __m512i low = _mm512_permutex2var_epi32(x, from, y);  // right where from < 32
        const __mmask16 high = _mm512_cmpge_epi32_mask(from, _mm512_set1_epi32(32));
        const __m512i second = _mm512_mask_blend_epi32(high, lane, _mm512_sub_epi32(from, _mm512_set1_epi32(16)));
        out[k]->v = _mm512_permutex2var_epi32(low, second, z);
    }
}

// The inverse of load_interleaved3: p[3i] = a[i], p[3i + 1] = b[i], p[3i + 2] = c[i] for the
// 3 * kLanes values from p (unaligned): per block of 16 values, a two-source permute of a and
// b with c's values blended in from a one-source permute.
inline void store_interleaved3(float* p, vfloat a, vfloat b, vfloat c) {
    // Value j of block k is p[16k + j]: stream (16k + j) mod 3, lane (16k + j) / 3.
    alignas(64) static constexpr int32_t kLane[48] = {0, 0, 0, 1, 1, 1, 2, 2, 2, 3, 3, 3, 4, 4, 4, 5,  //
                                                     5, 5, 6, 6, 6, 7, 7, 7, 8, 8, 8, 9, 9, 9, 10, 10,  //
                                                     10, 11, 11, 11, 12, 12, 12, 13, 13, 13, 14, 14, 14, 15, 15, 15};
    static constexpr __mmask16 kFromB[3] = {0x2492, 0x9249, 0x4924}, kFromC[3] = {0x4924, 0x2492, 0x9249};
    for (int k = 0; k < 3; ++k) {
        const __m512i i = _mm512_load_si512(kLane + 16 * k);
        const __m512i i_or_b = _mm512_mask_add_epi32(i, kFromB[k], i, _mm512_set1_epi32(16));  // b's lanes follow a's
        const __m512 ab = _mm512_permutex2var_ps(a.v, i_or_b, b.v);
        _mm512_storeu_ps(p + 16 * k, _mm512_mask_blend_ps(kFromC[k], ab, _mm512_permutexvar_ps(i, c.v)));
    }
}

// The lanes selected by `m` moved to the lowest lanes, in lane order; the other lanes zero.
inline vfloat compress(vmask m, vfloat a) { return _mm512_maskz_compress_ps(m.m, a.v); }
inline vint compress(vmask m, vint a) { return _mm512_maskz_compress_epi32(m.m, a.v); }

// Aligned stores of the lanes selected by `m`.
inline void store_masked(float* p, vmask m, vfloat a) { _mm512_mask_store_ps(p, m.m, a.v); }
inline void store_masked(uint32_t* p, vmask m, vint a) { _mm512_mask_store_epi32(p, m.m, a.v); }

// 128-bit blocks of x (result blocks 0, 1) and y (2, 3), chosen by the 2-bit fields of P.
template <int P>
inline __m512i blocks(__m512i x, __m512i y) { return _mm512_mask_shuffle_i32x4(x, kAllLanes, x, y, P); }

// Lane i of a, b, c, d to p[4i .. 4i + 3] (unaligned): kLanes RGBA pixels from their channels.
// Two 4x4 transposes: the unpacks leave lane 4j + k's four values in 128-bit block j of u_k,
// then a transpose of the 128-bit blocks puts lanes 4j .. 4j + 3 side by side.
inline void store_interleaved4(float* p, vfloat a, vfloat b, vfloat c, vfloat d) {
    const __m512 none = _mm512_setzero_ps();
    const __m512d zero = _mm512_setzero_pd();
    const auto pd = [](__m512 v) { return _mm512_castps_pd(v); };
    const __m512d t0 = pd(_mm512_mask_unpacklo_ps(none, kAllLanes, a.v, b.v));
    const __m512d t1 = pd(_mm512_mask_unpackhi_ps(none, kAllLanes, a.v, b.v));
    const __m512d t2 = pd(_mm512_mask_unpacklo_ps(none, kAllLanes, c.v, d.v));
    const __m512d t3 = pd(_mm512_mask_unpackhi_ps(none, kAllLanes, c.v, d.v));
    const auto si = [](__m512d v) { return _mm512_castpd_si512(v); };
    const __m512i u0 = si(_mm512_mask_unpacklo_pd(zero, 0xFF, t0, t2)), u1 = si(_mm512_mask_unpackhi_pd(zero, 0xFF, t0, t2));
    const __m512i u2 = si(_mm512_mask_unpacklo_pd(zero, 0xFF, t1, t3)), u3 = si(_mm512_mask_unpackhi_pd(zero, 0xFF, t1, t3));
    const __m512i v0 = blocks<0x44>(u0, u1), v1 = blocks<0x44>(u2, u3);  // u0 b0 b1, u1 b0 b1 / u2, u3
    const __m512i v2 = blocks<0xEE>(u0, u1), v3 = blocks<0xEE>(u2, u3);  // blocks 2, 3 of the same
    _mm512_storeu_si512(p, blocks<0x88>(v0, v1));
    _mm512_storeu_si512(p + 16, blocks<0xDD>(v0, v1));
    _mm512_storeu_si512(p + 32, blocks<0x88>(v2, v3));
    _mm512_storeu_si512(p + 48, blocks<0xDD>(v2, v3));
}

// Stamp layout to rows (simd.h): `stamps` holds kStampH horizontally adjacent 4x4 stamps
// (aligned, 64 values); row r of the 16 x 4 pixels they cover is written to dst + r * stride
// (unaligned), for r < rows. A 4x4 transpose of 128-bit blocks: block r of stamp s is row r.
inline void store_stamp_rows(const uint32_t* stamps, uint32_t* dst, size_t stride, int rows) {
    const __m512i a = _mm512_load_si512(stamps), b = _mm512_load_si512(stamps + 16);
    const __m512i c = _mm512_load_si512(stamps + 32), d = _mm512_load_si512(stamps + 48);
    const __m512i ab01 = blocks<0x44>(a, b), ab23 = blocks<0xEE>(a, b);  // a0 a1 b0 b1, a2 a3 b2 b3
    const __m512i cd01 = blocks<0x44>(c, d), cd23 = blocks<0xEE>(c, d);
    const __m512i row[4] = {blocks<0x88>(ab01, cd01), blocks<0xDD>(ab01, cd01),  // a0 b0 c0 d0, ...
                            blocks<0x88>(ab23, cd23), blocks<0xDD>(ab23, cd23)};
    for (int r = 0; r < rows; ++r) _mm512_storeu_si512(dst + size_t(r) * stride, row[r]);
}

// Copies n values to dst with non-temporal stores (no read of the destination lines, which
// bypass the caches): masked ordinary stores up to dst's first 64-byte boundary and after
// the last whole line. stream_fence() orders them before later stores (call it once done).
inline void stream_copy(uint32_t* dst, const uint32_t* src, size_t n) {
    const size_t misaligned = (reinterpret_cast<uintptr_t>(dst) & 63) / sizeof(uint32_t);
    const size_t head = std::min(n, (kLanes - misaligned) % kLanes);
    if (head) {
        const __mmask16 m = __mmask16((1u << head) - 1);
        _mm512_mask_storeu_epi32(dst, m, _mm512_maskz_loadu_epi32(m, src));
    }
    size_t i = head;
    for (; i + kLanes <= n; i += kLanes)
        _mm512_stream_si512(reinterpret_cast<__m512i*>(dst + i), _mm512_loadu_si512(src + i));
    if (i < n) {
        const __mmask16 m = __mmask16((1u << (n - i)) - 1);
        _mm512_mask_storeu_epi32(dst + i, m, _mm512_maskz_loadu_epi32(m, src + i));
    }
}
inline void stream_fence() { _mm_sfence(); }

}  // namespace tessera::simd

