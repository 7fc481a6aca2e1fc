#include "raster/shade/stamp_shading.h"

#include <tbb/enumerable_thread_specific.h>

#include <memory>

#include "raster/simd/simd.h"

namespace tessera::shade {

namespace {

using simd::kLanes;
using simd::vfloat;
using simd::vint;
using simd::vmask;

// One table record per triangle seen in the tile: barycentric planes e[0..2] (9 floats),
// positions (9), normals (9), uv (6).
constexpr int kEdges = 0, kPositions = 9, kNormals = 18, kUvs = 27, kRecord = 33;
constexpr uint32_t kLookup = 1u << 13;  // direct-mapped id -> slot cache, validated by slot_id

struct Scratch {
    std::vector<float> table;
    std::vector<uint32_t> slot_id;
    std::vector<int32_t> lookup = std::vector<int32_t>(kLookup, -1);
};

// Slot of triangle `id` in the tile's table; its attributes are fetched on first sight.
int32_t slot_of(const pipeline::TileContext& ctx, Scratch& s, uint32_t id) {
    int32_t& entry = s.lookup[id & (kLookup - 1)];
    if (entry >= 0 && size_t(entry) < s.slot_id.size() && s.slot_id[size_t(entry)] == id) return entry;
    TriangleAttributes t;
    fetch_triangle_attributes(ctx, id, t);
    entry = int32_t(s.slot_id.size());
    s.slot_id.push_back(id);
    const size_t base = s.table.size();
    s.table.resize(base + kRecord);
    float* r = &s.table[base];
    for (int k = 0; k < 3; ++k) {
        const glm::vec3& e = t.barycentrics.e[k];
        r[kEdges + 3 * k] = e.x, r[kEdges + 3 * k + 1] = e.y, r[kEdges + 3 * k + 2] = e.z;
        r[kPositions + 3 * k] = t.position[k].x, r[kPositions + 3 * k + 1] = t.position[k].y;
        r[kPositions + 3 * k + 2] = t.position[k].z;
        r[kNormals + 3 * k] = t.normal[k].x, r[kNormals + 3 * k + 1] = t.normal[k].y;
        r[kNormals + 3 * k + 2] = t.normal[k].z;
        r[kUvs + 2 * k] = t.uv[k].x, r[kUvs + 2 * k + 1] = t.uv[k].y;
    }
    return entry;
}

// glm's vec3 arithmetic in lanes, operation for operation (glm::dot is (x*x' + y*y') + z*z').
struct V3 {
    vfloat x, y, z;
};
V3 operator+(const V3& a, const V3& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
V3 operator-(const V3& a, const V3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
V3 operator*(vfloat s, const V3& a) { return {s * a.x, s * a.y, s * a.z}; }
vfloat dot(const V3& a, const V3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
V3 broadcast(const glm::vec3& v) { return {vfloat(v.x), vfloat(v.y), vfloat(v.z)}; }

// reference_shading.cpp's safe_normalize: v / |v|, 0 where |v| = 0.
V3 safe_normalize(const V3& v) {
    const vfloat length = simd::sqrt(dot(v, v));
    const vmask positive = vfloat(0.0f) < length;
    const vfloat zero(0.0f);
    return {simd::select(positive, v.x / length, zero), simd::select(positive, v.y / length, zero),
            simd::select(positive, v.z / length, zero)};
}

// x^48 = (((x^3)^2)^2)^2)^2: error bound in stamp_shading.h.
vfloat pow48(vfloat x) {
    vfloat p = x * x * x;
    p = p * p;
    p = p * p;
    p = p * p;
    return p * p;
}

vint quantise(vfloat c) {
    const vfloat clamped = simd::min(simd::max(c, vfloat(0.0f)), vfloat(1.0f));
    return simd::round_to_int(simd::floor(clamped * vfloat(255.0f) + vfloat(0.5f)));
}

// Normal or Phong colour of the lanes at row `y`, columns x + lane, from table slots `slot`.
void shade_lanes(ShadeMode mode, const PhongLight& phong, const float* table, vint slot, int x, int y,
                 vint& r8, vint& g8, vint& b8) {
    const vint base = slot * vint(kRecord);
    auto at = [&](int k) { return simd::gather(table + k, base); };
    const vfloat px = simd::to_float(vint(x) + simd::lane_index()) + vfloat(0.5f);
    const vfloat py(float(y) + 0.5f);
    // PerspectiveBarycentrics::at.
    const vfloat r0 = simd::fma(at(kEdges + 0), px, simd::fma(at(kEdges + 1), py, at(kEdges + 2)));
    const vfloat r1 = simd::fma(at(kEdges + 3), px, simd::fma(at(kEdges + 4), py, at(kEdges + 5)));
    const vfloat r2 = simd::fma(at(kEdges + 6), px, simd::fma(at(kEdges + 7), py, at(kEdges + 8)));
    const vfloat inv = vfloat(1.0f) / (r0 + r1 + r2);
    const vfloat l0 = r0 * inv, l1 = r1 * inv, l2 = r2 * inv;
    auto interpolate3 = [&](int k) {
        const V3 a{at(k), at(k + 1), at(k + 2)}, b{at(k + 3), at(k + 4), at(k + 5)}, c{at(k + 6), at(k + 7), at(k + 8)};
        return l0 * a + l1 * b + l2 * c;
    };
    const V3 n = safe_normalize(interpolate3(kNormals));
    V3 c;
    if (mode == ShadeMode::normal) {
        const vfloat half(0.5f);
        c = {n.x * half + half, n.y * half + half, n.z * half + half};
    } else {
        const V3 p = interpolate3(kPositions);
        const vfloat u = l0 * at(kUvs) + l1 * at(kUvs + 2) + l2 * at(kUvs + 4);
        const vfloat v_coord = l0 * at(kUvs + 1) + l1 * at(kUvs + 3) + l2 * at(kUvs + 5);
        const V3 v = safe_normalize(broadcast(phong.eye) - p);
        const vmask back = dot(n, v) < vfloat(0.0f);
        const vfloat minus(-1.0f);
        const V3 n2{simd::select(back, n.x * minus, n.x), simd::select(back, n.y * minus, n.y),
                    simd::select(back, n.z * minus, n.z)};
        const V3 lv = safe_normalize(broadcast(phong.light) - p);
        const V3 h = safe_normalize(lv + v);
        const vfloat s = simd::floor(u * vfloat(16.0f)) + simd::floor(v_coord * vfloat(8.0f));
        const vfloat checker = s - vfloat(2.0f) * simd::floor(s * vfloat(0.5f));
        // glm::mix(x, y, a) = x * (1 - a) + y * a.
        const vfloat keep = vfloat(1.0f) - checker;
        const V3 albedo = keep * broadcast({0.80f, 0.35f, 0.20f}) + checker * broadcast({0.90f, 0.85f, 0.70f});
        const vfloat diffuse = vfloat(0.08f) + vfloat(0.92f) * simd::max(dot(n2, lv), vfloat(0.0f));
        const vfloat specular = vfloat(0.5f) * pow48(simd::max(dot(n2, h), vfloat(0.0f)));
        c = {albedo.x * diffuse + specular, albedo.y * diffuse + specular, albedo.z * diffuse + specular};
    }
    r8 = quantise(c.x);
    g8 = quantise(c.y);
    b8 = quantise(c.z);
}

}  // namespace

pipeline::TilePass make_stamp_shading_pass(ShadeMode mode, const Camera& camera, std::vector<uint8_t>& rgb8) {
    const PhongLight phong = PhongLight::from(camera);
    auto scratch = std::make_shared<tbb::enumerable_thread_specific<Scratch>>();
    return [mode, phong, scratch, &rgb8](const pipeline::TileContext& ctx) {
        Scratch& s = scratch->local();
        s.table.clear();
        s.slot_id.clear();
        const int width = ctx.viewport->width;
        alignas(64) int32_t slots[kLanes];
        alignas(64) int32_t r[kLanes], g[kLanes], b[kLanes];
        for (int y = ctx.rect.y0; y < ctx.rect.y1; ++y) {
            const uint32_t* ids = ctx.triangle + size_t(y - ctx.rect.y0) * ctx.stride;
            const float* depth = ctx.depth + size_t(y - ctx.rect.y0) * ctx.stride;
            uint8_t* out = &rgb8[(size_t(y) * width + ctx.rect.x0) * 3];
            glm::vec4* color = ctx.colour ? ctx.colour + size_t(y - ctx.rect.y0) * ctx.colour_stride : nullptr;
            for (int x = ctx.rect.x0; x < ctx.rect.x1; x += kLanes) {
                const int n = std::min(kLanes, ctx.rect.x1 - x);
                const int i0 = x - ctx.rect.x0;
                bool any = false;
                for (int k = 0; k < kLanes; ++k) {
                    const uint32_t id = k < n ? ids[i0 + k] : kNoTriangle;
                    r[k] = g[k] = b[k] = 0;
                    slots[k] = 0;
                    if (id == kNoTriangle) continue;
                    any = true;
                    if (mode == ShadeMode::id) {
                        const uint32_t h = id_colour(id);
                        r[k] = quantise(float(h & 255) / 255.0f);
                        g[k] = quantise(float((h >> 8) & 255) / 255.0f);
                        b[k] = quantise(float((h >> 16) & 255) / 255.0f);
                    } else if (mode == ShadeMode::depth) {
                        r[k] = g[k] = b[k] = quantise(depth[i0 + k]);
                    } else {
                        slots[k] = k > 0 && ids[i0 + k] == ids[i0 + k - 1] ? slots[k - 1] : slot_of(ctx, s, id);
                    }
                }
                if (any && (mode == ShadeMode::normal || mode == ShadeMode::phong)) {
                    vint r8, g8, b8;
                    shade_lanes(mode, phong, s.table.data(), vint::load(slots), x, y, r8, g8, b8);
                    r8.store(r), g8.store(g), b8.store(b);
                    for (int k = 0; k < n; ++k)
                        if (ids[i0 + k] == kNoTriangle) r[k] = g[k] = b[k] = 0;
                }
                for (int k = 0; k < n; ++k) {
                    out[3 * (i0 + k)] = uint8_t(r[k]);
                    out[3 * (i0 + k) + 1] = uint8_t(g[k]);
                    out[3 * (i0 + k) + 2] = uint8_t(b[k]);
                }
                if (color)
                    for (int k = 0; k < n; ++k)
                        color[i0 + k] = glm::vec4(float(r[k]), float(g[k]), float(b[k]), 255.0f) / 255.0f;
            }
        }
    };
}

}  // namespace tessera::shade
