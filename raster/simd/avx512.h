// AVX-512 back end of simd.h: 16 float / int32 lanes, masks in k registers.
#pragma once
#include <immintrin.h>

#include <cstdint>

// GCC 12 reports the _mm512_undefined_ps() pass-through operand of its masked builtins
// (min, max, cvt) as maybe-uninitialized; it is unused by design.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"

namespace tessera::simd {

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
    void store(int32_t* p) const { _mm512_store_si512(p, v); }
};
inline vint operator+(vint a, vint b) { return _mm512_add_epi32(a.v, b.v); }
inline vint operator-(vint a, vint b) { return _mm512_sub_epi32(a.v, b.v); }
inline vint operator*(vint a, vint b) { return _mm512_mullo_epi32(a.v, b.v); }
inline vint operator&(vint a, vint b) { return _mm512_and_si512(a.v, b.v); }
inline vint operator|(vint a, vint b) { return _mm512_or_si512(a.v, b.v); }
inline vint operator>>(vint a, vint s) { return _mm512_srav_epi32(a.v, s.v); }
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
    void store(float* p) const { _mm512_store_ps(p, v); }
};
inline vfloat operator+(vfloat a, vfloat b) { return _mm512_add_ps(a.v, b.v); }
inline vfloat operator-(vfloat a, vfloat b) { return _mm512_sub_ps(a.v, b.v); }
inline vfloat operator*(vfloat a, vfloat b) { return _mm512_mul_ps(a.v, b.v); }
inline vfloat operator/(vfloat a, vfloat b) { return _mm512_div_ps(a.v, b.v); }
inline vfloat fma(vfloat a, vfloat b, vfloat c) { return _mm512_fmadd_ps(a.v, b.v, c.v); }
// min/max return the second operand when either is NaN, like the scalar `a < b ? a : b`.
inline vfloat min(vfloat a, vfloat b) { return _mm512_min_ps(a.v, b.v); }
inline vfloat max(vfloat a, vfloat b) { return _mm512_max_ps(a.v, b.v); }
inline vmask operator<(vfloat a, vfloat b) { return vmask(_mm512_cmp_ps_mask(a.v, b.v, _CMP_LT_OQ)); }
inline vmask operator<=(vfloat a, vfloat b) { return vmask(_mm512_cmp_ps_mask(a.v, b.v, _CMP_LE_OQ)); }
inline vfloat select(vmask m, vfloat a, vfloat b) { return _mm512_mask_blend_ps(m.m, b.v, a.v); }
inline vfloat to_float(vint a) { return _mm512_cvtepi32_ps(a.v); }
inline vfloat sqrt(vfloat a) { return _mm512_sqrt_ps(a.v); }
inline vint round_to_int(vfloat a) { return _mm512_cvtps_epi32(a.v); }  // nearest even
inline vfloat gather(const float* base, vint index) { return _mm512_i32gather_ps(index.v, base, 4); }

// Aligned stores of the lanes selected by `m`.
inline void store_masked(float* p, vmask m, vfloat a) { _mm512_mask_store_ps(p, m.m, a.v); }
inline void store_masked(uint32_t* p, vmask m, vint a) { _mm512_mask_store_epi32(p, m.m, a.v); }

}  // namespace tessera::simd

#pragma GCC diagnostic pop
