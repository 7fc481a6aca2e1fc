// Sub-pixel precision and the integer ranges of the rasterizer, chosen together so that no
// integer in setup or traversal can overflow (D3D11.3 §3.4.1, §15.16: vertices snapped to 16.8
// fixed point, round to nearest; 8 fractional bits exactly).
//
// Ranges, from the outside in:
// - Viewport: at most kMaxViewport = 8192 pixels per axis (checked by Viewport).
// - Guard band: clipping keeps every window coordinate within +-kCoordLimit = 16000 pixels
//   (< 2^14), so the band is at least 16000 - 8192 pixels wide on every side of the largest
//   viewport, and only triangles reaching beyond it are clipped (clip.h).
// - Snapped vertex X, Y (16.8): |X| <= 2^14 * 2^8 = 2^22, int32.
// - Edge deltas dX = Xb - Xa: |dX| <= 2^23, int32. They are also the per-pixel steps of the
//   reduced edge function F below (F(x+1, y) = F - dY, F(x, y+1) = F + dX).
// - Twice the signed area: |dX * dY'| + |dY * dX'| <= 2^47, int64.
// - Edge function at a pixel centre P inside the viewport:
//   E = dX*(Py - Ya) - dY*(Px - Xa), |E| <= 2 * 2^23 * 2^23 = 2^47, int64.
//   Since pixel centres sit on a 256-grid, E = 256*G(x, y) + K with integer G, and the fill rule
//   test "E + bias > 0" is exactly "F >= 0" with F = G + floor((K - 1 + bias) / 256)
//   (triangle_setup.h); |F| <= 2^39, int64 at triangle and tile level.
// - Inside a block of B x B pixels crossed by an edge (F < 0 somewhere, F >= 0 somewhere),
//   every |F| <= (|dX| + |dY|) * (B - 1) < 2^24 * B, so int32 lanes are exact for B <= 64; the
//   tile rasterizer uses B = 16 for big triangles.
// - A "small" triangle (vertex bounding box under kSmallExtent = 2^15 sub-pixels = 128 pixels
//   per axis) has |dX|, |dY| < 2^15 and |F| < 2^15 * (128 + 8) * 2 < 2^24 anywhere within 4
//   pixels of its box, so it is traversed with int32 lanes directly (the fast path).
#pragma once
#include <cstdint>

namespace tessera::pipeline {

inline constexpr int kSubpixelBits = 8;
inline constexpr int32_t kSubpixels = 1 << kSubpixelBits;  // per pixel, per axis
inline constexpr int kMaxViewport = 8192;
inline constexpr float kCoordLimit = 16000.0f;
inline constexpr int32_t kSmallExtent = 1 << 15;

static_assert(kCoordLimit < float(1 << 14), "snapped coordinates must stay within 2^22");
static_assert(kMaxViewport < kCoordLimit, "the guard band must contain the viewport");

}  // namespace tessera::pipeline
