// The SIMD form of `tessera raster --shade` (reference_shading.h defines the shaders): the
// same per-pixel formulas over simd::kLanes pixels at once, run on each tile while its
// visibility is in cache, writing finished 8-bit pixels.
//
// Where the rasterizer keeps the visibility in its tiles (RasterOptions::frame_visibility
// false, TileContext::stamps) the pass reads the tile buffers in their stamp layout, one stamp
// (4x4 pixels on 16 lanes) at a time, and writes kStampH stamps side by side as whole rows of
// the frame (simd::store_stamp_rows); otherwise it reads the tile's rows of the frame's
// visibility buffer, kLanes pixels of a row at a time. Either way each lane is the pixel the
// reference shades, with the same inputs.
//
// Per tile, each visible triangle's inputs (perspective barycentric planes, positions,
// normals, uv: TriangleAttributes) are fetched once into a tile-local table with the scalar
// fetch_triangle_attributes. Lanes that all show one triangle read its record as broadcast
// constants; others gather theirs by table slot. Every operation mirrors the reference in
// order and rounding (no contraction: the library builds with -ffp-contract=off), so id,
// depth and normal are bit-identical, and so are phong's barycentrics, N, V, L, H, the checker
// and N.L; the one difference is the specular power: x^48 is computed as (((x^3)^2)^2)^2)^2
// with 6 rounded multiplies instead of powf. Its relative error is at most 2u*16 + 15u = 47u
// (u = 2^-24, each squaring doubles the incoming relative error), i.e. < 2.9e-6, so the
// specular term 0.5*x^48 <= 0.5 moves by < 1.5e-6 and the 8-bit output (255 * colour) by
// < 4e-4 of a level: a channel differs from the reference only where the reference value lies
// that close to a rounding boundary, and then by exactly one level (tests/stamp_shading_test).
#pragma once
#include <cstdint>
#include <vector>

#include "raster/shade/reference_shading.h"

namespace tessera::shade {

// Same contract as make_reference_shading_pass (the pixels go to `rgba8`), except that
// ctx.colour is not written.
pipeline::TilePass make_stamp_shading_pass(ShadeMode mode, const Camera& camera, std::vector<uint32_t>& rgba8);

}  // namespace tessera::shade
