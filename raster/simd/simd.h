// One SIMD vocabulary for every kernel: vfloat, vint (int32) and vmask of kLanes lanes, chosen
// by the instruction set the compiler targets. Kernels are written once against these types so
// they read like the math ("e = f + step; m = e >= 0"); the width follows the build:
//   __AVX512F__ -> 16 lanes (avx512.h), __AVX2__ -> 8 lanes (avx2.h), otherwise 1 lane
//   (scalar.h, builds anywhere and is the executable definition of what the others compute).
//
// Every operation is exact IEEE single precision per lane (fma is a fused multiply-add in all
// three), so a kernel gives bit-identical results at any width: the scalar reference paths
// and the tests rely on that.
#pragma once

#if defined(__AVX512F__)
#include "raster/simd/avx512.h"
#elif defined(__AVX2__)
#include "raster/simd/avx2.h"
#else
#include "raster/simd/scalar.h"
#endif

namespace tessera::simd {

// bits() of a mask with every lane set: the test for "the whole group" on lane masks.
inline constexpr uint32_t kEveryLaneBits = kLanes == 32 ? ~0u : (1u << kLanes) - 1u;

// A 2D "stamp" of pixels processed by one instruction: 4x4 for 16 lanes, 4x2 for 8, 1x1 for 1.
inline constexpr int kStampW = kLanes >= 4 ? 4 : 1;
inline constexpr int kStampH = kLanes / kStampW;
static_assert(kStampW * kStampH == kLanes);

// Lane i of a stamp covers pixel (i % kStampW, i / kStampW) relative to the stamp's corner.
inline vint stamp_x() { return lane_index() & vint(kStampW - 1); }
inline vint stamp_y() {
    if constexpr (kStampW == 1) return vint(0);
    return lane_index() >> vint(kStampW == 4 ? 2 : 0);
}

// store_stamp_rows(stamps, dst, stride, rows) (in each back end): kStampH horizontally
// adjacent stamps, stored contiguously as a tile keeps them, cover kLanes x kStampH pixels;
// it writes their rows 0 .. rows-1 (rows <= kStampH) as kLanes consecutive values each to
// dst + r * stride. The bits are copied unchanged (float data goes through as uint32_t).
//
// stream_copy(dst, src, n) / stream_fence(): a copy whose stores bypass the caches (for
// output nothing reads soon: they save reading each destination line before writing it).
//
// store_interleaved4(p, a, b, c, d): lane i of the four to p[4i .. 4i + 3], the channels of
// kLanes RGBA float pixels stored as a tile's colour buffer keeps them (glm::vec4 per pixel).
//
// gather_quads(base, q, a, b, c, d): per lane i, the four floats base[4 q_i .. 4 q_i + 3]
// into lane i of a, b, c, d (q_i < 2^29): an RGBA float texel per lane, fetched as the same
// bits as four gather() calls would fetch them.

}  // namespace tessera::simd
