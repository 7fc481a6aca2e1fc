// Transparent triangles over a multisampled layer (core/coverage_layers.h), with the
// semantics of hardware MSAA: a transparent fragment is shaded once per pixel (at its centre),
// its coverage and depth test are per sample, and its colour is blended into the colour of
// each sample it covers; the resolve then averages the samples in linear light.
//
// Most fragments cover every sample of the layer's surface in their pixel; those pixels keep
// one colour and go through the ordinary per-pixel path (alpha test, then blending, in
// submission order), at its cost and with its bytes. A pixel where some fragment covers only
// part of the surface's samples is split instead: its samples are grouped by what they show
// (the nearest surviving alpha-tested fragment, or the layer's surface, and the blended
// fragments in front of it), and each group becomes a surface of its own, with the group's
// sample count as its coverage and its first sample as its centroid. The layer keeps the
// group of its first sample; the other groups go into extra tiles of the same form as a
// layer, which the remaining passes (shadows, blending, compute passes) run on like any
// layer. fold() then averages each split pixel's groups by their samples into the layer's
// colour, so the resolve weighs each group by its own samples: exactly per-sample colours,
// computed once per distinct group rather than once per sample.
//
// Alpha-tested fragments are shaded (and their alpha tested) once per pixel; where they
// survive they are the opaque surface of the samples they cover. Between an alpha-tested and
// a blended fragment of one pixel, which is in front is decided on the fragments' depths (the
// nearest of their covered samples), as the one-sample path decides it at the pixel centre.
#pragma once
#include <glm/glm.hpp>

#include <cstdint>
#include <span>
#include <vector>

#include "raster/core/tile.h"
#include "raster/shade/alpha_test.h"
#include "raster/shade/frame_shading.h"

namespace tessera::render {

class LayerSplit {
public:
    // `layer` after its surfaces and background are shaded; `masked` (with `masked_colours`,
    // shade::shade_alpha_tested) and `blended`: its transparent fragments in submission order.
    // Takes the fragments of split pixels out of the three lists (what is left goes the
    // ordinary way) and sets up main() and the extra tiles; writes the layer's triangle, depth
    // and colour where a surviving alpha-tested fragment wins its first sample's group.
    // Returns whether any pixel was split. A layer that is not multisampled is never split.
    bool split(const Tile& layer, std::vector<shade::DepthFragment>& masked, std::vector<glm::vec4>& masked_colours,
               std::vector<shade::DepthFragment>& blended);

    // The layer as the remaining passes see it: coverage, sample masks and centroids of split
    // pixels narrowed to their first group.
    const Tile& main() const { return main_; }
    // The blended fragments each split pixel's first group shows, in submission order (blend
    // them into main() without a depth test: they are decided).
    std::span<const shade::CoveredPixel> main_blended() const { return main_blended_; }
    int extra_tiles() const { return int(extra_.size()); }
    const Tile& extra(int k) const { return extra_[size_t(k)].tile; }
    std::span<const shade::CoveredPixel> extra_blended(int k) const { return extra_[size_t(k)].blended; }

    // After the passes: each split pixel's colour in main() the average of its groups' colours
    // weighted by their samples.
    void fold() const;

private:
    struct Group {
        int32_t winner;  // index into the masked list, -1: the layer's surface
        uint16_t mask;
        int count;
        int first;                        // its first sample
        uint32_t blended_begin, blended_end;  // its blended fragments: group_blended_'s range
    };
    struct Extra {
        Tile tile;
        std::vector<uint32_t> triangle;
        std::vector<float> depth;
        std::vector<glm::vec4> colour;
        std::vector<uint8_t> coverage;
        std::vector<glm::vec2> centroid;
        std::vector<uint16_t> mask;
        std::vector<shade::CoveredPixel> blended;
    };
    // A group of a split pixel that goes into an extra tile, before the tile is laid out.
    struct Entry {
        int x, y;
        uint32_t triangle;
        float depth;
        glm::vec4 colour;
        int count;
        glm::vec2 centroid;
        uint16_t mask;
        uint32_t blended_begin, blended_end;  // its blended fragments: entry_blended_'s range
    };
    // A split pixel and how many samples the layer gives it.
    struct Pixel {
        int x, y;
        int samples;
    };

    Tile main_;
    std::vector<uint8_t> coverage_;
    std::vector<uint16_t> mask_;
    std::vector<glm::vec2> centroid_;
    std::vector<shade::CoveredPixel> main_blended_;
    std::vector<Extra> extra_;
    std::vector<Pixel> pixels_;
    // Scratch, kept from layer to layer.
    std::vector<int32_t> slot_;
    std::vector<std::vector<uint32_t>> masked_of_, blended_of_;
    std::vector<Group> groups_;
    std::vector<uint32_t> shown_, group_blended_, entry_blended_;
    std::vector<std::vector<Entry>> entries_;
};

}  // namespace tessera::render
