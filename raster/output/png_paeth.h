// PNG's Paeth filter (ISO/IEC 15948 section 9.4, Alan W. Paeth's predictor) on the encoder's
// side: residual = x - predictor(a, b, c), where a is the byte bpp to the left in the row, b
// the byte above, c the byte above and to the left (0 left of the first pixel, so there the
// predictor is b). The encoder reads only the unfiltered rows, so every byte is independent of
// the others: the row filters in whole vectors of bytes.
//
// paeth_residuals is the fast form: 64 bytes per step on AVX-512BW, 32 on AVX2, computed in
// 8-bit lanes. With p = a + b - c the predictor compares
//     pa = |p - a| = |b - c|,  pb = |p - b| = |a - c|,  pc = |p - c| = |(a - c) + (b - c)|;
// pa and pb fit a byte; pc is pa + pb when a - c and b - c have the same sign and |pa - pb|
// otherwise, and pa + pb is taken with unsigned saturation: a sum past 255 is no smaller than
// pa or pb either way, so the two comparisons with pc come out the same. The compiler's own
// vectorisation of the scalar loop widens to 16-bit lanes, half as many bytes per instruction.
// paeth_residuals_reference is the predictor as the standard writes it, byte by byte: the
// tests hold the fast form to it for every (a, b, c) and for rows of every length and bpp.
#pragma once
#include <cstddef>
#include <cstdint>

namespace tessera::output {

// The Paeth residuals of a row of n bytes, bpp bytes per pixel (1 <= bpp), into out[0 .. n).
// `up` is the row above (zeros above the first row). out may not overlap row or up.
void paeth_residuals_reference(const uint8_t* row, const uint8_t* up, size_t n, size_t bpp, uint8_t* out);
void paeth_residuals(const uint8_t* row, const uint8_t* up, size_t n, size_t bpp, uint8_t* out);

}  // namespace tessera::output
