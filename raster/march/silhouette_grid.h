// Which pixels of a multisampled tile a ray-marched surface's silhouette may cross: the pixels
// whose centre ray's result differs from a neighbour's. A surface's edge inside a pixel puts
// the pixel's centre and some neighbouring centre on different sides of it (hit and miss, or
// hits on two surfaces at very different distances: a near ball in front of a far one, a
// ridge in front of the valley behind it), so comparing each centre with its 8 neighbours
// finds the pixels that need their samples marched, from results the centres have anyway.
// This is the discontinuity test of selective supersampling ("adaptive antialiasing" in
// Whitted's 1980 ray tracer, which subdivides where neighbouring samples differ); features
// thinner than a pixel that fall between centres are not found, as there.
//
// The grid holds the tile's centres and a one-pixel ring around them (the neighbour tiles'
// centres, marched again here, so the tile needs nothing from the tiles beside it).
#pragma once
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace tessera::march {

class SilhouetteGrid {
public:
    // Distances along the centre ray: a hit, kNoHit (a miss), or kUnknown (a pixel whose
    // centre was not marched: another surface's pixel in this layer, or outside the image;
    // it is not compared).
    static constexpr float kNoHit = INFINITY;
    static constexpr float kUnknown = -1.0f;
    // Two hits differ when their distances differ by more than this fraction of the nearer
    // one: a continuous surface seen at pixel spacing changes far less, except within about a
    // degree of grazing, which is a silhouette's neighbourhood anyway.
    static constexpr float kDistanceJump = 1.0f / 16.0f;

    // A w x h tile with its ring, every entry kUnknown.
    void reset(int w, int h) {
        w_ = w;
        h_ = h;
        at_.assign(size_t(w + 2) * size_t(h + 2), kUnknown);
    }
    // Entry of tile pixel (i, j) relative to the tile's first pixel; -1 and w / h are the ring.
    float& at(int i, int j) { return at_[size_t(j + 1) * size_t(w_ + 2) + size_t(i + 1)]; }
    float at(int i, int j) const { return at_[size_t(j + 1) * size_t(w_ + 2) + size_t(i + 1)]; }

    static bool differ(float a, float b) {
        if (a == b) return false;  // the common case: two misses, or one surface
        if (a == kUnknown || b == kUnknown) return false;
        if ((a == kNoHit) != (b == kNoHit)) return true;
        if (a == kNoHit) return false;
        return std::fabs(a - b) > kDistanceJump * std::fmin(a, b);
    }
    // Marks every entry that differs from one of its 8 neighbours: each neighbouring pair
    // is compared once (right, down and both diagonals of every entry), row by row.
    void mark_edges() {
        const size_t stride = size_t(w_ + 2);
        edge_.assign(at_.size(), 0);
        for (size_t j = 0; j + 1 < size_t(h_ + 2); ++j) {
            const float* a = &at_[j * stride];
            const float* b = a + stride;
            uint8_t* ea = &edge_[j * stride];
            uint8_t* eb = ea + stride;
            for (size_t i = 0; i + 1 < stride; ++i) {
                if (differ(a[i], a[i + 1])) ea[i] = ea[i + 1] = 1;
                if (differ(a[i], b[i])) ea[i] = eb[i] = 1;
                if (differ(a[i], b[i + 1])) ea[i] = eb[i + 1] = 1;
                if (differ(a[i + 1], b[i])) ea[i + 1] = eb[i] = 1;
            }
            if (differ(a[stride - 1], b[stride - 1])) ea[stride - 1] = eb[stride - 1] = 1;
        }
    }
    // After mark_edges: whether tile pixel (i, j) differs from a neighbour (an unknown pixel
    // never does).
    bool edge(int i, int j) const { return edge_[size_t(j + 1) * size_t(w_ + 2) + size_t(i + 1)] != 0; }

private:
    int w_ = 0, h_ = 0;
    std::vector<float> at_;
    std::vector<uint8_t> edge_;
};

}  // namespace tessera::march
