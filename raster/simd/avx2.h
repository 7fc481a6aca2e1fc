// AVX2 back end of simd.h: 8 float / int32 lanes, masks as all-ones / all-zeros lanes.
#pragma once
#include <immintrin.h>

#include <algorithm>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <cstring>

namespace tessera::simd {

inline constexpr int kLanes = 8;

struct vmask {
    __m256i m;
    vmask() : m(_mm256_setzero_si256()) {}
    explicit vmask(__m256i k) : m(k) {}
    explicit vmask(bool b) : m(_mm256_set1_epi32(b ? -1 : 0)) {}
};
inline vmask operator&(vmask a, vmask b) { return vmask(_mm256_and_si256(a.m, b.m)); }
inline vmask operator|(vmask a, vmask b) { return vmask(_mm256_or_si256(a.m, b.m)); }
inline vmask andnot(vmask a, vmask b) { return vmask(_mm256_andnot_si256(a.m, b.m)); }
inline uint32_t bits(vmask a) { return uint32_t(_mm256_movemask_ps(_mm256_castsi256_ps(a.m))); }
inline bool any(vmask a) { return bits(a) != 0; }
inline bool all(vmask a) { return bits(a) == 0xFF; }

struct vint {
    __m256i v;
    vint() : v(_mm256_setzero_si256()) {}
    vint(__m256i x) : v(x) {}
    vint(int32_t s) : v(_mm256_set1_epi32(s)) {}
    static vint load(const int32_t* p) { return _mm256_load_si256(reinterpret_cast<const __m256i*>(p)); }
    static vint load_unaligned(const int32_t* p) { return _mm256_loadu_si256(reinterpret_cast<const __m256i*>(p)); }
    void store(int32_t* p) const { _mm256_store_si256(reinterpret_cast<__m256i*>(p), v); }
    void store_unaligned(int32_t* p) const { _mm256_storeu_si256(reinterpret_cast<__m256i*>(p), v); }
};
inline vint operator+(vint a, vint b) { return _mm256_add_epi32(a.v, b.v); }
inline vint operator-(vint a, vint b) { return _mm256_sub_epi32(a.v, b.v); }
inline vint operator*(vint a, vint b) { return _mm256_mullo_epi32(a.v, b.v); }
inline vint operator&(vint a, vint b) { return _mm256_and_si256(a.v, b.v); }
inline vint operator|(vint a, vint b) { return _mm256_or_si256(a.v, b.v); }
inline vint operator^(vint a, vint b) { return _mm256_xor_si256(a.v, b.v); }
inline vint min(vint a, vint b) { return _mm256_min_epi32(a.v, b.v); }
inline vint max(vint a, vint b) { return _mm256_max_epi32(a.v, b.v); }
inline vint operator>>(vint a, vint s) { return _mm256_srav_epi32(a.v, s.v); }
// Shifts by a constant count in [0, 31]: left, and right filling with zeros (logical).
template <int N>
inline vint shift_left(vint a) { return _mm256_slli_epi32(a.v, N); }
template <int N>
inline vint shift_right_logical(vint a) { return _mm256_srli_epi32(a.v, N); }
inline int32_t first_lane(vint a) { return _mm256_cvtsi256_si32(a.v); }
// Lane i (0 <= i < kLanes), without a round trip through memory.
inline int32_t lane(vint a, int i) { return _mm256_cvtsi256_si32(_mm256_permutevar8x32_epi32(a.v, _mm256_set1_epi32(i))); }
inline vmask operator<(vint a, vint b) { return vmask(_mm256_cmpgt_epi32(b.v, a.v)); }
inline vmask operator>=(vint a, vint b) { return andnot(a < b, vmask(true)); }
inline vmask operator==(vint a, vint b) { return vmask(_mm256_cmpeq_epi32(a.v, b.v)); }
inline vint select(vmask m, vint a, vint b) {
    return _mm256_castps_si256(_mm256_blendv_ps(_mm256_castsi256_ps(b.v), _mm256_castsi256_ps(a.v),
                                                 _mm256_castsi256_ps(m.m)));
}
inline vint lane_index() { return _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7); }

struct vfloat {
    __m256 v;
    vfloat() : v(_mm256_setzero_ps()) {}
    vfloat(__m256 x) : v(x) {}
    vfloat(float s) : v(_mm256_set1_ps(s)) {}
    static vfloat load(const float* p) { return _mm256_load_ps(p); }
    static vfloat load_unaligned(const float* p) { return _mm256_loadu_ps(p); }
    void store(float* p) const { _mm256_store_ps(p, v); }
    void store_unaligned(float* p) const { _mm256_storeu_ps(p, v); }
};
inline vfloat operator+(vfloat a, vfloat b) { return _mm256_add_ps(a.v, b.v); }
inline vfloat operator-(vfloat a, vfloat b) { return _mm256_sub_ps(a.v, b.v); }
inline vfloat operator*(vfloat a, vfloat b) { return _mm256_mul_ps(a.v, b.v); }
inline vfloat operator/(vfloat a, vfloat b) { return _mm256_div_ps(a.v, b.v); }
inline vfloat fma(vfloat a, vfloat b, vfloat c) { return _mm256_fmadd_ps(a.v, b.v, c.v); }
inline vfloat min(vfloat a, vfloat b) { return _mm256_min_ps(a.v, b.v); }
inline vfloat max(vfloat a, vfloat b) { return _mm256_max_ps(a.v, b.v); }
inline vmask operator<(vfloat a, vfloat b) {
    return vmask(_mm256_castps_si256(_mm256_cmp_ps(a.v, b.v, _CMP_LT_OQ)));
}
inline vmask operator<=(vfloat a, vfloat b) {
    return vmask(_mm256_castps_si256(_mm256_cmp_ps(a.v, b.v, _CMP_LE_OQ)));
}
inline vfloat select(vmask m, vfloat a, vfloat b) {
    return _mm256_blendv_ps(b.v, a.v, _mm256_castsi256_ps(m.m));
}
inline vfloat to_float(vint a) { return _mm256_cvtepi32_ps(a.v); }
inline vfloat sqrt(vfloat a) { return _mm256_sqrt_ps(a.v); }
inline vfloat floor(vfloat a) { return _mm256_floor_ps(a.v); }
inline vint round_to_int(vfloat a) { return _mm256_cvtps_epi32(a.v); }  // nearest even
inline vfloat gather(const float* base, vint index) { return _mm256_i32gather_ps(base, index.v, 4); }

// Lane i of a, b, c, d = base[4 q_i .. 4 q_i + 3] (simd.h): one float gather per channel.
inline void gather_quads(const float* base, vint quad, vfloat& a, vfloat& b, vfloat& c, vfloat& d) {
    const __m256i i = _mm256_slli_epi32(quad.v, 2);
    a.v = _mm256_i32gather_ps(base, i, 4);
    b.v = _mm256_i32gather_ps(base + 1, i, 4);
    c.v = _mm256_i32gather_ps(base + 2, i, 4);
    d.v = _mm256_i32gather_ps(base + 3, i, 4);
}

// The bits of each lane as the other type (no conversion).
inline vint bits_of(vfloat a) { return _mm256_castps_si256(a.v); }
inline vfloat float_of_bits(vint a) { return _mm256_castsi256_ps(a.v); }
// The low byte of each lane to p[0 .. kLanes) (unaligned).
inline void store_low_bytes(uint8_t* p, vint a) {
    const __m256i low = _mm256_shuffle_epi8(
        a.v, _mm256_setr_epi8(0, 4, 8, 12, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1,  //
                              0, 4, 8, 12, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1));
    const uint64_t bytes = uint64_t(uint32_t(_mm256_extract_epi32(low, 0))) |
                           uint64_t(uint32_t(_mm256_extract_epi32(low, 4))) << 32;
    std::memcpy(p, &bytes, 8);
}

// The three streams of 3 * kLanes consecutive values: a[i] = p[3i], b[i] = p[3i + 1],
// c[i] = p[3i + 2] (gathered).
inline void load_interleaved3(const int32_t* p, vint& a, vint& b, vint& c) {
    const __m256i from = _mm256_mullo_epi32(lane_index().v, _mm256_set1_epi32(3));
    a = _mm256_i32gather_epi32(p, from, 4);
    b = _mm256_i32gather_epi32(p + 1, from, 4);
    c = _mm256_i32gather_epi32(p + 2, from, 4);
}

// The inverse of load_interleaved3: p[3i] = a[i], p[3i + 1] = b[i], p[3i + 2] = c[i] for the
// 3 * kLanes values from p (unaligned), one value at a time (AVX2 has no scatter).
inline void store_interleaved3(float* p, vfloat a, vfloat b, vfloat c) {
    alignas(32) float v[3][kLanes];
    a.store(v[0]), b.store(v[1]), c.store(v[2]);
    for (int i = 0; i < kLanes; ++i)
        for (int s = 0; s < 3; ++s) p[3 * i + s] = v[s][i];
}

// The lanes selected by `m` moved to the lowest lanes, in lane order; the other lanes zero
// (through memory: AVX2 has no compress).
template <class V, class T>
inline V compress_lanes(vmask m, V a) {
    alignas(32) T in[kLanes], out[kLanes] = {};
    a.store(in);
    int n = 0;
    for (uint32_t k = bits(m); k; k &= k - 1) out[n++] = in[std::countr_zero(k)];
    return V::load(out);
}
inline vfloat compress(vmask m, vfloat a) { return compress_lanes<vfloat, float>(m, a); }
inline vint compress(vmask m, vint a) { return compress_lanes<vint, int32_t>(m, a); }

// Stores of the lanes selected by `m`: load, blend, store (the tile owns the whole line).
inline void store_masked(float* p, vmask m, vfloat a) { select(m, a, vfloat::load(p)).store(p); }
inline void store_masked(uint32_t* p, vmask m, vint a) {
    int32_t* q = reinterpret_cast<int32_t*>(p);
    select(m, a, vint::load(q)).store(q);
}

// Lane i of a, b, c, d to p[4i .. 4i + 3] (unaligned), as in avx512.h: the unpacks leave lane
// 4j + k's quad in half j of u_k; the halves are then paired.
inline void store_interleaved4(float* p, vfloat a, vfloat b, vfloat c, vfloat d) {
    const auto pd = [](__m256 v) { return _mm256_castps_pd(v); };
    const auto ps = [](__m256d v) { return _mm256_castpd_ps(v); };
    const __m256d t0 = pd(_mm256_unpacklo_ps(a.v, b.v)), t1 = pd(_mm256_unpackhi_ps(a.v, b.v));
    const __m256d t2 = pd(_mm256_unpacklo_ps(c.v, d.v)), t3 = pd(_mm256_unpackhi_ps(c.v, d.v));
    const __m256 u0 = ps(_mm256_unpacklo_pd(t0, t2)), u1 = ps(_mm256_unpackhi_pd(t0, t2));
    const __m256 u2 = ps(_mm256_unpacklo_pd(t1, t3)), u3 = ps(_mm256_unpackhi_pd(t1, t3));
    _mm256_storeu_ps(p, _mm256_permute2f128_ps(u0, u1, 0x20));
    _mm256_storeu_ps(p + 8, _mm256_permute2f128_ps(u2, u3, 0x20));
    _mm256_storeu_ps(p + 16, _mm256_permute2f128_ps(u0, u1, 0x31));
    _mm256_storeu_ps(p + 24, _mm256_permute2f128_ps(u2, u3, 0x31));
}

// Stamp layout to rows (simd.h): `stamps` holds kStampH horizontally adjacent 4x2 stamps
// (aligned, 16 values); row r of the 8 x 2 pixels they cover is written to dst + r * stride
// (unaligned), for r < rows. Row r of a stamp is its 128-bit half r.
inline void store_stamp_rows(const uint32_t* stamps, uint32_t* dst, size_t stride, int rows) {
    const __m256i a = _mm256_load_si256(reinterpret_cast<const __m256i*>(stamps));
    const __m256i b = _mm256_load_si256(reinterpret_cast<const __m256i*>(stamps + 8));
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(dst), _mm256_permute2x128_si256(a, b, 0x20));
    if (rows > 1)
        _mm256_storeu_si256(reinterpret_cast<__m256i*>(dst + stride), _mm256_permute2x128_si256(a, b, 0x31));
}

// Copies n values to dst with non-temporal stores (no read of the destination lines, which
// bypass the caches): ordinary stores up to dst's first 32-byte boundary and after the last
// whole vector. stream_fence() orders them before later stores (call it once done).
inline void stream_copy(uint32_t* dst, const uint32_t* src, size_t n) {
    const size_t misaligned = (reinterpret_cast<uintptr_t>(dst) & 31) / sizeof(uint32_t);
    const size_t head = std::min(n, (kLanes - misaligned) % kLanes);
    size_t i = 0;
    for (; i < head; ++i) dst[i] = src[i];
    for (; i + kLanes <= n; i += kLanes)
        _mm256_stream_si256(reinterpret_cast<__m256i*>(dst + i),
                            _mm256_loadu_si256(reinterpret_cast<const __m256i*>(src + i)));
    for (; i < n; ++i) dst[i] = src[i];
}
inline void stream_fence() { _mm_sfence(); }

}  // namespace tessera::simd
