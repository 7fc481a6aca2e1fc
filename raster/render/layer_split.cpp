#include "raster/render/layer_split.h"

#include <algorithm>
#include <limits>

#include "raster/core/visibility.h"

namespace tessera::render {

bool LayerSplit::split(const Tile& layer, std::vector<shade::DepthFragment>& masked,
                       std::vector<glm::vec4>& masked_colours, std::vector<shade::DepthFragment>& blended) {
    main_ = layer;
    main_blended_.clear();
    extra_.clear();
    pixels_.clear();
    if (!layer.multisampled() || (masked.empty() && blended.empty())) return false;
    const TileRect& r = layer.rect;
    const size_t w = size_t(r.width()), area = w * size_t(r.height());
    const auto local = [&](int x, int y) { return size_t(y - r.y0) * w + size_t(x - r.x0); };
    const auto partial = [&](const shade::DepthFragment& f) {
        return f.mask != layer.samples_at(f.x, f.y);
    };
    // The pixels to split: some surviving alpha-tested or some blended fragment covers only
    // part of the layer's samples there.
    slot_.assign(area, -1);
    bool any = false;
    for (size_t i = 0; i < masked.size(); ++i)
        if (shade::survives(masked_colours[i]) && partial(masked[i])) slot_[local(masked[i].x, masked[i].y)] = 0, any = true;
    for (const shade::DepthFragment& f : blended)
        if (partial(f)) slot_[local(f.x, f.y)] = 0, any = true;
    if (!any) return false;
    for (int y = r.y0; y < r.y1; ++y)
        for (int x = r.x0; x < r.x1; ++x)
            if (int32_t& slot = slot_[local(x, y)]; slot == 0) {
                slot = int32_t(pixels_.size());
                pixels_.push_back({x, y, int(layer.coverage[layer.offset(x, y)])});
            }
    const size_t n_pixels = pixels_.size();
    masked_of_.resize(std::max(masked_of_.size(), n_pixels));
    blended_of_.resize(std::max(blended_of_.size(), n_pixels));
    for (size_t k = 0; k < n_pixels; ++k) masked_of_[k].clear(), blended_of_[k].clear();
    // The split pixels' fragments leave the lists (kept in order for what stays).
    std::vector<shade::DepthFragment> all_masked, all_blended;
    all_masked.swap(masked);
    all_blended.swap(blended);
    std::vector<glm::vec4> all_colours;
    all_colours.swap(masked_colours);
    std::vector<shade::DepthFragment>& keep_masked = masked;
    for (size_t i = 0; i < all_masked.size(); ++i) {
        const int32_t slot = slot_[local(all_masked[i].x, all_masked[i].y)];
        if (slot < 0) {
            keep_masked.push_back(all_masked[i]);
            masked_colours.push_back(all_colours[i]);
        } else if (shade::survives(all_colours[i])) {
            masked_of_[size_t(slot)].push_back(uint32_t(i));
        }
    }
    for (size_t i = 0; i < all_blended.size(); ++i) {
        const int32_t slot = slot_[local(all_blended[i].x, all_blended[i].y)];
        if (slot < 0) blended.push_back(all_blended[i]);
        else blended_of_[size_t(slot)].push_back(uint32_t(i));
    }

    // The layer's per-pixel coverage, masks and centroids as main() hands them out.
    const size_t extent = layer.stride * size_t(r.height() - 1) + w;
    coverage_.assign(layer.coverage, layer.coverage + extent);
    mask_.assign(layer.sample_mask, layer.sample_mask + extent);
    main_.coverage = coverage_.data();
    main_.sample_mask = mask_.data();
    if (layer.centroid) {
        centroid_.assign(layer.centroid, layer.centroid + extent);
        main_.centroid = centroid_.data();
    }
    const int n = layer.sample_count;
    const glm::vec2* positions = layer.sample_offsets;
    for (auto& e : entries_) e.clear();
    entry_blended_.clear();
    size_t extras = 0;
    for (size_t k = 0; k < n_pixels; ++k) {
        const Pixel& p = pixels_[k];
        const size_t off = layer.offset(p.x, p.y);
        const uint16_t samples = layer.samples_at(p.x, p.y);
        const std::vector<uint32_t>& m = masked_of_[k];
        const std::vector<uint32_t>& b = blended_of_[k];
        // Per sample of the layer's surface: the nearest surviving alpha-tested fragment
        // covering it (its coverage mask says it is in front of the surface), then the blended
        // fragments covering it in front of that; samples that show the same form a group.
        groups_.clear();
        group_blended_.clear();
        for (int s = 0; s < n; ++s) {
            if (!((samples >> s) & 1)) continue;
            int32_t winner = -1;
            float nearest = std::numeric_limits<float>::infinity();
            for (const uint32_t i : m)
                if ((all_masked[i].mask >> s) & 1 && (winner < 0 || all_masked[i].depth < nearest))
                    winner = int32_t(i), nearest = all_masked[i].depth;
            shown_.clear();
            for (const uint32_t j : b)
                if ((all_blended[j].mask >> s) & 1 && (winner < 0 || all_blended[j].depth < nearest)) shown_.push_back(j);
            const auto same = [&](const Group& group) {
                return group.winner == winner &&
                       std::equal(group_blended_.begin() + group.blended_begin, group_blended_.begin() + group.blended_end,
                                  shown_.begin(), shown_.end());
            };
            size_t g = 0;
            while (g < groups_.size() && !same(groups_[g])) ++g;
            if (g == groups_.size()) {
                const uint32_t begin = uint32_t(group_blended_.size());
                group_blended_.insert(group_blended_.end(), shown_.begin(), shown_.end());
                groups_.push_back({winner, 0, 0, s, begin, uint32_t(group_blended_.size())});
            }
            groups_[g].mask = uint16_t(groups_[g].mask | (1u << s));
            ++groups_[g].count;
        }
        const glm::vec4 surface_colour = layer.colour_at(p.x, p.y);
        const uint32_t surface_triangle = layer.triangle_at(p.x, p.y);
        const float surface_depth = layer.depth_at(p.x, p.y);
        const glm::vec2 surface_centroid = layer.centroid ? layer.centroid[off] : glm::vec2(0.0f);
        for (size_t g = 0; g < groups_.size(); ++g) {
            const Group& group = groups_[g];
            const bool own = group.winner >= 0;
            const shade::DepthFragment* winner = own ? &all_masked[size_t(group.winner)] : nullptr;
            const uint32_t triangle = own ? winner->triangle : surface_triangle;
            const float depth = own ? winner->depth : surface_depth;
            const glm::vec4 colour =
                own ? glm::vec4(glm::vec3(all_colours[size_t(group.winner)]), 1.0f) : surface_colour;
            // An alpha-tested surface partly covering the pixel is evaluated on itself (at
            // its first sample); the layer's surface where the layer evaluates it.
            const glm::vec2 centroid = !own ? surface_centroid : group.count == n ? glm::vec2(0.0f) : positions[group.first];
            if (g == 0) {
                layer.triangle_at(p.x, p.y) = triangle;
                layer.depth_at(p.x, p.y) = depth;
                layer.colour_at(p.x, p.y) = colour;
                coverage_[off] = uint8_t(group.count);
                mask_[off] = group.mask;
                if (layer.centroid) centroid_[off] = centroid;
                for (uint32_t i = group.blended_begin; i < group.blended_end; ++i)
                    main_blended_.push_back({p.x, p.y, all_blended[group_blended_[i]].triangle});
                continue;
            }
            extras = std::max(extras, g);
            if (entries_.size() < g) entries_.resize(g);
            const uint32_t begin = uint32_t(entry_blended_.size());
            entry_blended_.insert(entry_blended_.end(), group_blended_.begin() + group.blended_begin,
                                  group_blended_.begin() + group.blended_end);
            entries_[g - 1].push_back({p.x, p.y, triangle, depth, colour, group.count, centroid, group.mask, begin,
                                       uint32_t(entry_blended_.size())});
        }
    }

    // Each extra tile over the box of its pixels, laid out as a layer (CoverageLayers::layer):
    // pixels it does not hold have no coverage, no triangle and the nearest depth.
    extra_.resize(extras);
    for (size_t k = 0; k < extras; ++k) {
        const std::vector<Entry>& entries = entries_[k];
        TileRect box{r.x1, r.y1, r.x0, r.y0};
        for (const Entry& e : entries) {
            box.x0 = std::min(box.x0, e.x);
            box.y0 = std::min(box.y0, e.y);
            box.x1 = std::max(box.x1, e.x + 1);
            box.y1 = std::max(box.y1, e.y + 1);
        }
        Extra& x = extra_[k];
        const size_t bw = size_t(box.width()), barea = bw * size_t(box.height());
        x.triangle.assign(barea, kNoTriangle);
        x.depth.assign(barea, 0.0f);
        x.colour.assign(barea, glm::vec4(0.0f));
        x.coverage.assign(barea, 0);
        x.centroid.assign(barea, glm::vec2(0.0f));
        x.mask.assign(barea, 0);
        x.blended.clear();
        for (const Entry& e : entries) {
            const size_t i = size_t(e.y - box.y0) * bw + size_t(e.x - box.x0);
            x.triangle[i] = e.triangle;
            x.depth[i] = e.depth;
            x.colour[i] = e.colour;
            x.coverage[i] = uint8_t(e.count);
            x.centroid[i] = e.centroid;
            x.mask[i] = e.mask;
            for (uint32_t j = e.blended_begin; j < e.blended_end; ++j)
                x.blended.push_back({e.x, e.y, all_blended[entry_blended_[j]].triangle});
        }
        Tile& t = x.tile;
        t = Tile{};
        t.rect = box;
        t.triangle = x.triangle.data();
        t.depth = x.depth.data();
        t.stride = bw;
        t.colour = x.colour.data();
        t.colour_stride = bw;
        t.coverage = x.coverage.data();
        t.centroid = x.centroid.data();
        t.sample_mask = x.mask.data();
        t.sample_count = n;
        t.sample_offsets = positions;
    }
    return true;
}

void LayerSplit::fold() const {
    for (const Pixel& p : pixels_) {
        const size_t off = main_.offset(p.x, p.y);
        glm::vec4 sum = main_.colour_at(p.x, p.y) * float(coverage_[off]);
        for (const Extra& x : extra_) {
            const TileRect& b = x.tile.rect;
            if (p.x < b.x0 || p.x >= b.x1 || p.y < b.y0 || p.y >= b.y1) continue;
            const uint8_t count = x.tile.coverage[x.tile.offset(p.x, p.y)];
            if (count) sum += x.tile.colour_at(p.x, p.y) * float(count);
        }
        main_.colour_at(p.x, p.y) = sum / float(p.samples);
    }
}

}  // namespace tessera::render
