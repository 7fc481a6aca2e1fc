#include "raster/output/png_paeth.h"

#include <algorithm>
#include <cstdlib>

namespace tessera::output {
namespace {

uint8_t paeth_predictor(int a, int b, int c) {
    const int p = a + b - c;
    const int pa = std::abs(p - a), pb = std::abs(p - b), pc = std::abs(p - c);
    return uint8_t(pa <= pb && pa <= pc ? a : (pb <= pc ? b : c));
}

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
    // The others in a branch-free form the compiler vectorises (16-bit lanes), pa, pb, pc as
    // in the header.
    for (size_t i = first; i < n; ++i) {
        const int a = row[i - bpp], b = up[i], c = up[i - bpp];
        const int pa = std::abs(b - c), pb = std::abs(a - c), pc = std::abs(a + b - 2 * c);
        out[i] = uint8_t(row[i] - (pa <= pb && pa <= pc ? a : (pb <= pc ? b : c)));
    }
}

}  // namespace tessera::output
