#include "raster/shadow/shadow_edges.h"

namespace tessera::shadow {

void find_shadow_edges(const Tile& tile, size_t image_width, const SurfacePoints& points,
                       std::span<const uint8_t> lights, int samples, std::vector<uint16_t>& scratch,
                       std::vector<uint32_t>& edges) {
    const TileRect& r = tile.rect;
    const int w = r.width(), h = r.height();
    // The lights of each pixel of the tile that has a point; kNone (above any 8-bit set of
    // lights) where it has none.
    constexpr uint16_t kNone = 0x100;
    scratch.assign(size_t(w) * size_t(h), kNone);
    const auto local = [&](uint32_t pixel) {
        const int x = int(pixel % image_width) - r.x0, y = int(pixel / image_width) - r.y0;
        return size_t(y) * size_t(w) + size_t(x);
    };
    for (size_t i = 0; i < points.size(); ++i) scratch[local(points.pixel[i])] = lights[i];
    for (size_t i = 0; i < points.size(); ++i) {
        const uint32_t pixel = points.pixel[i];
        const int x = int(pixel % image_width), y = int(pixel / image_width);
        if (tile.coverage && tile.coverage[tile.offset(x, y)] != samples) continue;
        const size_t at = local(pixel);
        const int lx = x - r.x0, ly = y - r.y0;
        const bool border = lx == 0 || ly == 0 || lx == w - 1 || ly == h - 1;
        const uint16_t own = lights[i];
        const auto differs = [&](size_t n) { return scratch[n] != kNone && scratch[n] != own; };
        if (border || differs(at - 1) || differs(at + 1) || differs(at - size_t(w)) || differs(at + size_t(w)))
            edges.push_back(uint32_t(i));
    }
}

}  // namespace tessera::shadow
