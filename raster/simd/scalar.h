// The scalar "SIMD" fallback: one lane, plain C++. It is also the reference for what each
// operation of the wider back ends means (see simd.h).
#pragma once
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>

namespace tessera::simd {

inline constexpr int kLanes = 1;

struct vmask {
    bool m = false;
    vmask() = default;
    explicit vmask(bool b) : m(b) {}
};
inline vmask operator&(vmask a, vmask b) { return vmask(a.m && b.m); }
inline vmask operator|(vmask a, vmask b) { return vmask(a.m || b.m); }
inline vmask andnot(vmask a, vmask b) { return vmask(!a.m && b.m); }  // ~a & b
inline bool any(vmask a) { return a.m; }
inline bool all(vmask a) { return a.m; }
inline uint32_t bits(vmask a) { return a.m ? 1u : 0u; }

struct vint {
    int32_t v = 0;
    vint() = default;
    vint(int32_t s) : v(s) {}
    static vint load(const int32_t* p) { return vint(p[0]); }
    static vint load_unaligned(const int32_t* p) { return vint(p[0]); }
    void store(int32_t* p) const { p[0] = v; }
    void store_unaligned(int32_t* p) const { p[0] = v; }
};
// Wrapping arithmetic like the hardware lanes (computed in uint32 to avoid C++ UB).
inline vint operator+(vint a, vint b) { return vint(int32_t(uint32_t(a.v) + uint32_t(b.v))); }
inline vint operator-(vint a, vint b) { return vint(int32_t(uint32_t(a.v) - uint32_t(b.v))); }
inline vint operator*(vint a, vint b) { return vint(int32_t(uint32_t(a.v) * uint32_t(b.v))); }
inline vint operator&(vint a, vint b) { return vint(a.v & b.v); }
inline vint operator|(vint a, vint b) { return vint(a.v | b.v); }
inline vint operator^(vint a, vint b) { return vint(a.v ^ b.v); }
inline vint min(vint a, vint b) { return a.v < b.v ? a : b; }
inline vint max(vint a, vint b) { return a.v < b.v ? b : a; }
inline vint operator>>(vint a, vint s) { return vint(a.v >> s.v); }  // arithmetic
// Shifts by a constant count in [0, 31]: left, and right filling with zeros (logical).
template <int N>
inline vint shift_left(vint a) { return vint(int32_t(uint32_t(a.v) << N)); }
template <int N>
inline vint shift_right_logical(vint a) { return vint(int32_t(uint32_t(a.v) >> N)); }
inline int32_t first_lane(vint a) { return a.v; }
// Lane i (0 <= i < kLanes), without a round trip through memory.
inline int32_t lane(vint a, int) { return a.v; }
inline vmask operator>=(vint a, vint b) { return vmask(a.v >= b.v); }
inline vmask operator<(vint a, vint b) { return vmask(a.v < b.v); }
inline vmask operator==(vint a, vint b) { return vmask(a.v == b.v); }
inline vint select(vmask m, vint a, vint b) { return m.m ? a : b; }
inline vint lane_index() { return vint(0); }

struct vfloat {
    float v = 0.0f;
    vfloat() = default;
    vfloat(float s) : v(s) {}
    static vfloat load(const float* p) { return vfloat(p[0]); }
    static vfloat load_unaligned(const float* p) { return vfloat(p[0]); }
    void store(float* p) const { p[0] = v; }
    void store_unaligned(float* p) const { p[0] = v; }
};
inline vfloat operator+(vfloat a, vfloat b) { return a.v + b.v; }
inline vfloat operator-(vfloat a, vfloat b) { return a.v - b.v; }
inline vfloat operator*(vfloat a, vfloat b) { return a.v * b.v; }
inline vfloat operator/(vfloat a, vfloat b) { return a.v / b.v; }
inline vfloat fma(vfloat a, vfloat b, vfloat c) { return std::fma(a.v, b.v, c.v); }  // a*b+c
inline vfloat min(vfloat a, vfloat b) { return a.v < b.v ? a.v : b.v; }
inline vfloat max(vfloat a, vfloat b) { return a.v > b.v ? a.v : b.v; }
inline vmask operator<(vfloat a, vfloat b) { return vmask(a.v < b.v); }
inline vmask operator<=(vfloat a, vfloat b) { return vmask(a.v <= b.v); }
inline vfloat select(vmask m, vfloat a, vfloat b) { return m.m ? a : b; }
inline vfloat to_float(vint a) { return float(a.v); }
inline vfloat sqrt(vfloat a) { return std::sqrt(a.v); }
inline vfloat floor(vfloat a) { return std::floor(a.v); }
// Round to nearest, ties to even (the default rounding mode, like cvtps2dq).
inline vint round_to_int(vfloat a) { return vint(int32_t(std::nearbyint(a.v))); }
inline vfloat gather(const float* base, vint index) { return base[index.v]; }

// a, b, c, d = base[4q .. 4q + 3] (simd.h).
inline void gather_quads(const float* base, vint quad, vfloat& a, vfloat& b, vfloat& c, vfloat& d) {
    const float* q = base + 4 * size_t(uint32_t(quad.v));
    a = q[0];
    b = q[1];
    c = q[2];
    d = q[3];
}

// The bits of each lane as the other type (no conversion).
inline vint bits_of(vfloat a) {
    int32_t b;
    std::memcpy(&b, &a.v, 4);
    return vint(b);
}
inline vfloat float_of_bits(vint a) {
    float f;
    std::memcpy(&f, &a.v, 4);
    return vfloat(f);
}
// The low byte of each lane to p[0 .. kLanes).
inline void store_low_bytes(uint8_t* p, vint a) { p[0] = uint8_t(a.v); }

// The three streams of 3 * kLanes consecutive values: a[i] = p[3i], b[i] = p[3i + 1],
// c[i] = p[3i + 2].
// a, b, c, d to p[0 .. 3]: one RGBA pixel from its channels.
inline void store_interleaved4(float* p, vfloat a, vfloat b, vfloat c, vfloat d) {
    p[0] = a.v;
    p[1] = b.v;
    p[2] = c.v;
    p[3] = d.v;
}

inline void load_interleaved3(const int32_t* p, vint& a, vint& b, vint& c) {
    a = vint(p[0]);
    b = vint(p[1]);
    c = vint(p[2]);
}

// The inverse of load_interleaved3: p[0] = a, p[1] = b, p[2] = c.
inline void store_interleaved3(float* p, vfloat a, vfloat b, vfloat c) {
    p[0] = a.v;
    p[1] = b.v;
    p[2] = c.v;
}

// The lanes selected by `m` moved to the lowest lanes, in lane order; the other lanes zero.
inline vfloat compress(vmask m, vfloat a) { return m.m ? a : vfloat(0.0f); }
inline vint compress(vmask m, vint a) { return m.m ? a : vint(0); }

// Stores the lanes of `a` where `m` is set (the others keep their memory contents).
inline void store_masked(float* p, vmask m, vfloat a) { if (m.m) p[0] = a.v; }
inline void store_masked(uint32_t* p, vmask m, vint a) { if (m.m) p[0] = uint32_t(a.v); }

// Stamp layout to rows (simd.h): with one-pixel stamps, the one stamp is the one row.
inline void store_stamp_rows(const uint32_t* stamps, uint32_t* dst, size_t, int rows) {
    if (rows > 0) dst[0] = stamps[0];
}

// Copies n values (the portable build has no non-temporal stores: ordinary ones).
inline void stream_copy(uint32_t* dst, const uint32_t* src, size_t n) {
    std::memcpy(dst, src, n * sizeof(uint32_t));
}
inline void stream_fence() {}

}  // namespace tessera::simd
