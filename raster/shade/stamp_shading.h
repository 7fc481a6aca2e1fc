// The SIMD form of `tessera raster --shade` (reference_shading.h defines the shaders): the
// same per-pixel formulas over simd::kLanes pixels of a row at once.
//
// Per tile, each visible triangle's inputs (perspective barycentric planes, positions,
// normals, uv: TriangleAttributes) are fetched once into a tile-local table with the scalar
// fetch_triangle_attributes, and the lanes gather them by table slot. Every operation mirrors
// the reference in order and rounding (no contraction: the library builds with
// -ffp-contract=off), so barycentrics, N, V, L, H, the checker and N.L are bit-identical; the
// one difference is the specular power: x^48 is computed as (((x^3)^2)^2)^2)^2 with
// 6 rounded multiplies instead of powf. Its relative error is at most 2u*16 + 15u = 47u
// (u = 2^-24, each squaring doubles the incoming relative error), i.e. < 2.9e-6, so the
// specular term 0.5*x^48 <= 0.5 moves by < 1.5e-6 and the 8-bit output (255 * colour) by
// < 4e-4 of a level: a channel differs from the reference only where the reference value lies
// that close to a rounding boundary, and then by exactly one level (tests/stamp_shading_test).
#pragma once
#include <cstdint>
#include <vector>

#include "raster/shade/reference_shading.h"

namespace tessera::shade {

// Same contract as make_reference_shading_pass, except that ctx.colour (when the rasterizer
// gives a colour tile) receives the quantised colour, channel / 255.
pipeline::TilePass make_stamp_shading_pass(ShadeMode mode, const Camera& camera, std::vector<uint8_t>& rgb8);

}  // namespace tessera::shade
