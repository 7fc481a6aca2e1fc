#include "raster/shade/outline.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "raster/simd/simd.h"

namespace tessera::shade {
namespace {

// w = 1 / d from window depth z = z_ndc * 0.5 + 0.5: the inverse of the perspective's z row,
// d = 2 n f / (f + n - z_ndc (f - n)), so w is affine in z (and in screen space on a plane).
struct InverseDistance {
    double n, f;
    float operator()(float z) const {
        const double z_ndc = 2.0 * double(z) - 1.0;
        return float((f + n - z_ndc * (f - n)) / (2.0 * n * f));
    }
};

bool is_background(float depth) { return !(depth < 1.0f); }

}  // namespace

bool any_outlined(std::span<const scene::Material> materials) {
    return std::any_of(materials.begin(), materials.end(),
                       [](const scene::Material& m) { return m.model == scene::ShadingModel::toon; });
}

void draw_outlines_reference(const VisibilityBuffer& visibility, const Camera& camera,
                             std::span<const uint32_t> triangle_material, std::span<const scene::Material> materials,
                             std::vector<glm::vec4>& colour, int row_begin, int row_end) {
    const int w = visibility.width, h = visibility.height;
    row_begin = std::max(row_begin, 0);
    row_end = std::min(row_end, h);
    if (row_begin >= row_end || !any_outlined(materials)) return;
    const InverseDistance inverse{camera.near, camera.far};

    // The material of what pixel i shows; marched surfaces (no triangle) have none.
    constexpr uint32_t kNoMaterial = 0xFFFFFFFFu;
    const auto material_at = [&](size_t i) {
        const uint32_t t = visibility.triangle[i];
        return t < triangle_material.size() ? triangle_material[t] : kNoMaterial;
    };
    // Along one axis through p (material m, inverse distance wp): is p on the near side of an
    // edge? At the frame's border only the neighbour that exists counts, and not for the crease.
    const auto edge = [&](uint32_t m, float wp, int ax, int ay, int bx, int by, bool has_a, bool has_b) {
        float w_side[2] = {wp, wp};
        const int xs[2] = {ax, bx}, ys[2] = {ay, by};
        const bool has[2] = {has_a, has_b};
        for (int k = 0; k < 2; ++k) {
            if (!has[k]) continue;
            const size_t q = size_t(ys[k]) * size_t(w) + size_t(xs[k]);
            if (is_background(visibility.depth[q])) return true;
            w_side[k] = inverse(visibility.depth[q]);
            if (material_at(q) != m && w_side[k] < wp) return true;  // another material behind
        }
        if (!has_a || !has_b) return false;
        const float step = (wp - std::min(w_side[0], w_side[1])) / wp;          // > 0: one lies farther
        const float crease = std::fabs(w_side[0] + w_side[1] - 2.0f * wp) / wp;  // 0 across a plane
        return step > kOutlineStep && crease > kOutlineStep;
    };

    for (int y = row_begin; y < row_end; ++y)
            for (int x = 0; x < w; ++x) {
                const size_t i = size_t(y) * size_t(w) + size_t(x);
                const uint32_t t = visibility.triangle[i];
                if (t == kNoTriangle || t >= triangle_material.size()) continue;
                const uint32_t m = triangle_material[t];
                if (m >= materials.size() || materials[m].model != scene::ShadingModel::toon) continue;
                const float wp = inverse(visibility.depth[i]);
                if (!(wp > 0.0f)) continue;
                if (edge(m, wp, x - 1, y, x + 1, y, x > 0, x + 1 < w) || edge(m, wp, x, y - 1, x, y + 1, y > 0, y + 1 < h))
                    colour[i] = glm::vec4(0.0f, 0.0f, 0.0f, colour[i].a);
            }
}

void draw_outlines(const VisibilityBuffer& visibility, const Camera& camera,
                   std::span<const uint32_t> triangle_material, std::span<const scene::Material> materials,
                   std::vector<glm::vec4>& colour, int row_begin, int row_end) {
    const OutlinePass pass(visibility, camera, triangle_material, materials);
    if (!pass.active()) return;
    tbb::parallel_for(tbb::blocked_range<int>(std::max(row_begin, 0), std::min(row_end, visibility.height), 8),
                      [&](const tbb::blocked_range<int>& rows) { pass.run(colour, rows.begin(), rows.end()); });
}

OutlinePass::OutlinePass(const VisibilityBuffer& visibility, const Camera& camera,
                         std::span<const uint32_t> triangle_material, std::span<const scene::Material> materials)
    : visibility_(visibility), near_(camera.near), far_(camera.far), triangle_material_(triangle_material) {
    toon_.resize(materials.size());
    for (size_t m = 0; m < materials.size(); ++m) {
        toon_[m] = materials[m].model == scene::ShadingModel::toon;
        active_ |= toon_[m] != 0;
    }
}

void OutlinePass::run(std::vector<glm::vec4>& colour, int row_begin, int row_end) const {
    run_rows(
        [&](size_t i) {
            glm::vec4& p = colour[i];
            p = glm::vec4(0.0f, 0.0f, 0.0f, p.a);
        },
        row_begin, row_end);
}

void OutlinePass::run(uint8_t* rgba8, int row_begin, int row_end) const {
    run_rows([&](size_t i) { rgba8[4 * i] = rgba8[4 * i + 1] = rgba8[4 * i + 2] = 0; }, row_begin, row_end);
}

template <class Ink>
void OutlinePass::run_rows(const Ink& ink, int row_begin, int row_end) const {
    using simd::kLanes;
    using simd::vfloat;
    using simd::vint;
    using simd::vmask;
    const int w = visibility_.width, h = visibility_.height;
    row_begin = std::max(row_begin, 0);
    row_end = std::min(row_end, h);
    if (row_begin >= row_end || !active_) return;
    const InverseDistance inverse{near_, far_};

    // What the tests read of one row, at index x + 1 (one slot of padding each side, and a
    // vector's worth after, so that the lanes' neighbour loads stay inside): 1/distance, the
    // material shown (-1 for none), and whether it is background (-1) or not (0).
    struct Row {
        std::vector<float> w;
        std::vector<int32_t> material, background;
    };
    const size_t padded = size_t(w) + 2 + size_t(kLanes);
    thread_local Row rows[3];  // kept from call to call: a band of rows is a few kB of work
    const auto floats = [](const float* p) { return vfloat::load_unaligned(p); };
    const auto ints = [](const int32_t* p) { return vint::load_unaligned(p); };
    const auto put = [](int32_t* p, vint v) { std::memcpy(p, &v, sizeof v); };
    const vint no(0), none(-1);
    // Triangle ids at or above this have no material (kNoTriangle included: negative as int32).
    const int32_t material_limit = int32_t(std::min<size_t>(triangle_material_.size(), size_t(INT32_MAX)));
    const auto load = [&](int y, Row& r) {
        // Every slot is written below: the padding here, the row's slots by the loops.
        r.w.resize(padded);
        r.material.resize(padded);
        r.background.resize(padded);
        r.w[0] = 0.0f, r.material[0] = -1, r.background[0] = 0;
        std::fill(r.w.begin() + w + 1, r.w.end(), 0.0f);
        std::fill(r.material.begin() + w + 1, r.material.end(), -1);
        std::fill(r.background.begin() + w + 1, r.background.end(), 0);
        const float* depth = visibility_.depth.data() + size_t(y) * size_t(w);
        const uint32_t* triangle = visibility_.triangle.data() + size_t(y) * size_t(w);
        float* rw = r.w.data() + 1;
        for (int x = 0; x < w; ++x) rw[x] = inverse(depth[x]);  // vectorises (double lanes)
        int32_t* material = r.material.data() + 1;
        int32_t* background = r.background.data() + 1;
        int x = 0;
        if (material_limit > 0) {
            // The material lookup as a gather, background as a compare: in lanes, the same
            // values as the loop below.
            const float* table = reinterpret_cast<const float*>(triangle_material_.data());
            for (; x + kLanes <= w; x += kLanes) {
                const vint t = ints(reinterpret_cast<const int32_t*>(triangle + x));
                const vmask known = (t >= no) & (t < vint(material_limit));
                put(material + x, simd::select(known, simd::bits_of(simd::gather(table, simd::select(known, t, no))), none));
                put(background + x, simd::select(floats(depth + x) < vfloat(1.0f), no, none));
            }
        }
        for (; x < w; ++x) {
            const uint32_t t = triangle[x];
            material[x] = t < triangle_material_.size() ? int32_t(triangle_material_[t]) : -1;
            background[x] = is_background(depth[x]) ? -1 : 0;
        }
    };
    const int32_t toon_count = int32_t(toon_.size());
    const vfloat zero(0.0f), step_limit(kOutlineStep);
    const vint lanes = simd::lane_index();
    Row* above = &rows[0];
    Row* here = &rows[1];
    Row* below = &rows[2];
    if (row_begin > 0) load(row_begin - 1, *above);
    load(row_begin, *here);
    for (int y = row_begin; y < row_end; ++y) {
        if (y + 1 < h) load(y + 1, *below);
        const vmask up(y > 0), down(y + 1 < h);
        const size_t row = size_t(y) * size_t(w);
        for (int x = 0; x < w; x += kLanes) {
            const size_t c = size_t(x) + 1;  // this lane block's first pixel in the rows
            const vint column = vint(x) + lanes;
            const vint m = ints(&here->material[c]);
            // A pixel of a toon material (draw_outlines_reference's tests, lane by lane).
            const vmask known = (m >= no) & (m < vint(toon_count)) & (column < vint(w));
            const vint toon = simd::bits_of(simd::gather(reinterpret_cast<const float*>(toon_.data()), simd::select(known, m, no)));
            const vfloat wp = floats(&here->w[c]);
            const vmask candidate = known & (toon == vint(1)) & (zero < wp);
            if (!simd::any(candidate)) continue;
            // A neighbour that is background, or shows another material farther away.
            const auto side = [&](const Row& r, size_t q) {
                const vint bg = ints(&r.background[q]);
                return (bg == vint(-1)) | (andnot(ints(&r.material[q]) == m, vmask(true)) & (floats(&r.w[q]) < wp));
            };
            // A crease with one side farther: std::min, then the two relative measures.
            const auto crease = [&](vfloat a, vfloat b) {
                const vfloat nearer = simd::select(b < a, b, a);
                const vfloat step = (wp - nearer) / wp;
                const vfloat sum = (a + b) - vfloat(2.0f) * wp;
                const vfloat bend = simd::float_of_bits(simd::bits_of(sum) & vint(0x7FFFFFFF)) / wp;
                return (step_limit < step) & (step_limit < bend);
            };
            const vmask left = vint(0) < column, right = column + vint(1) < vint(w);
            vmask inked = (left & side(*here, c - 1)) | (right & side(*here, c + 1)) |
                          (left & right & crease(floats(&here->w[c - 1]), floats(&here->w[c + 1])));
            if (y > 0) inked = inked | (up & side(*above, c));
            if (y + 1 < h) inked = inked | (down & side(*below, c));
            if (y > 0 && y + 1 < h) inked = inked | crease(floats(&above->w[c]), floats(&below->w[c]));
            for (uint32_t bits = simd::bits(inked & candidate); bits; bits &= bits - 1)
                ink(row + size_t(x + std::countr_zero(bits)));
        }
        std::swap(above, here);
        std::swap(here, below);
    }
}

}  // namespace tessera::shade
