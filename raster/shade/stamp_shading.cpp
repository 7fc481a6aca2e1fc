#include "raster/shade/stamp_shading.h"

#include <tbb/enumerable_thread_specific.h>

#include <bit>
#include <cstddef>
#include <cstring>
#include <memory>
#include <type_traits>

#include "procedural/hash.h"
#include "raster/simd/lane_math.h"
#include "raster/simd/simd.h"

namespace tessera::shade {

namespace {

using simd::kLanes;
using simd::kStampH;
using simd::kStampW;
using simd::vfloat;
using simd::vint;
using simd::vmask;

// One table record per triangle seen in the tile is its TriangleAttributes, fetched straight
// into the table and read as floats: barycentric planes e[0..2] (9 floats), positions (9),
// normals (9), uv (6), after the id. Building it in place rather than copying a fetched struct
// into a packed float record saves a copy of 132 bytes per record whose narrow loads read back
// the fetch's wide stores (a store-forwarding stall each).
static_assert(std::is_standard_layout_v<TriangleAttributes> && sizeof(TriangleAttributes) % sizeof(float) == 0);
constexpr int float_offset(size_t bytes) { return int(bytes / sizeof(float)); }
constexpr int kEdges = float_offset(offsetof(TriangleAttributes, barycentrics));
constexpr int kPositions = float_offset(offsetof(TriangleAttributes, position));
constexpr int kNormals = float_offset(offsetof(TriangleAttributes, normal));
constexpr int kUvs = float_offset(offsetof(TriangleAttributes, uv));
constexpr int kRecord = float_offset(sizeof(TriangleAttributes));
static_assert(kPositions == kEdges + 9 && kNormals == kPositions + 9 && kUvs == kNormals + 9 && kRecord == kUvs + 6,
              "the shading reads the record as 33 packed floats after the id");
constexpr uint32_t kLookup = 1u << 13;  // direct-mapped id -> slot cache, validated by slot_id

constexpr uint32_t kOpaque = 0xFF000000u;  // alpha 255: every pixel is finished
const vint kBackground{int32_t(kOpaque)};   // black, as the reference leaves empty pixels

// The triangles visible in one tile, each with its shading inputs in one record (slot).
// The id -> slot lookup is a direct-mapped cache whose entries are trusted only when the slot
// they name is live and holds that id, so a new tile starts by forgetting the count alone.
struct TriangleTable {
    std::vector<TriangleAttributes> records;
    std::vector<int32_t> slot_id{-1};  // id per slot; never shrinks, so every lookup entry indexes it
    std::vector<int32_t> lookup = std::vector<int32_t>(kLookup, 0);
    int32_t count = 0;

    // The record floats of slot 0 (slot s starts kRecord floats further on).
    const float* floats() const { return reinterpret_cast<const float*>(records.data()); }

    // Out of line: without it GCC inlines insert into find() and then keeps find() out of
    // Shader::shade, a call per stamp where most stamps find their triangles already in the
    // table.
    [[gnu::noinline]] int32_t insert(const pipeline::TileContext& ctx, uint32_t id) {
        const int32_t slot = count++;
        if (slot_id.size() < size_t(count)) slot_id.resize(size_t(count));
        if (records.size() < size_t(count)) records.resize(size_t(count));
        slot_id[size_t(slot)] = int32_t(id);
        lookup[id & (kLookup - 1)] = slot;
        fetch_triangle_attributes(ctx, id, records[size_t(slot)]);
        return slot;
    }

    int32_t find(const pipeline::TileContext& ctx, uint32_t id) {
        const int32_t slot = lookup[id & (kLookup - 1)];
        if (slot < count && slot_id[size_t(slot)] == int32_t(id)) return slot;
        return insert(ctx, id);
    }

    // The slots of the covered lanes' ids (0 elsewhere): the lookup in lanes, then the
    // triangles seen for the first time inserted one id at a time.
    vint find(const pipeline::TileContext& ctx, vint ids, vmask covered) {
        vint slots = simd::gather_int(lookup.data(), ids & vint(int32_t(kLookup - 1)));
        const vmask live = slots < vint(count);
        vmask missing = andnot(live & (simd::gather_int(slot_id.data(), slots) == ids), covered);
        while (simd::any(missing)) {
            const int32_t id = simd::lane(ids, std::countr_zero(simd::bits(missing)));
            const vmask same = ids == vint(id);
            slots = simd::select(same, vint(insert(ctx, uint32_t(id))), slots);
            missing = andnot(same, missing);
        }
        return simd::select(covered, slots, vint(0));
    }
};

// Record values of the lanes: one triangle's, broadcast ...
struct Broadcast {
    const float* record;
    vfloat operator()(int k) const { return vfloat(record[k]); }
};
// ... or those of a few triangles, each broadcast and chosen per lane (lanes[i - 1]: the
// lanes of record[i]; those of record[0] are the rest) ...
template <int N>
struct Blend {
    const float* record[N];
    vmask lanes[N - 1];
    vfloat operator()(int k) const {
        vfloat v(record[0][k]);
        for (int i = 1; i < N; ++i) v = simd::select(lanes[i - 1], vfloat(record[i][k]), v);
        return v;
    }
};
// ... or each lane's own, gathered by slot.
struct Gather {
    const float* records;
    vint base;  // slot * kRecord
    vfloat operator()(int k) const { return simd::gather(records + k, base); }
};

// glm's vec3 arithmetic in lanes, operation for operation (glm::dot is (x*x' + y*y') + z*z').
struct V3 {
    vfloat x, y, z;
};
V3 operator+(const V3& a, const V3& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
V3 operator-(const V3& a, const V3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
V3 operator*(vfloat s, const V3& a) { return {s * a.x, s * a.y, s * a.z}; }
vfloat dot(const V3& a, const V3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
V3 broadcast(const glm::vec3& v) { return {vfloat(v.x), vfloat(v.y), vfloat(v.z)}; }

// reference_shading.cpp's safe_normalize: v * (1 / |v|), 0 where |v| = 0.
V3 safe_normalize(const V3& v) {
    const vfloat length = simd::sqrt(dot(v, v));
    const vmask positive = vfloat(0.0f) < length;
    const vfloat inverse = vfloat(1.0f) / length;
    const vfloat zero(0.0f);
    return {simd::select(positive, v.x * inverse, zero), simd::select(positive, v.y * inverse, zero),
            simd::select(positive, v.z * inverse, zero)};
}

// x^48 = (((x^3)^2)^2)^2)^2: error bound in stamp_shading.h.
vfloat pow48(vfloat x) {
    vfloat p = x * x * x;
    p = p * p;
    p = p * p;
    p = p * p;
    return p * p;
}

// quantise() of reference_shading.h in lanes.
vint quantise(vfloat c) {
    const vfloat clamped = simd::min(simd::max(c, vfloat(0.0f)), vfloat(1.0f));
    return simd::round_to_int(simd::floor(clamped * vfloat(255.0f) + vfloat(0.5f)));
}

// 8-bit channels (each in [0, 255]) to an opaque RGBA8 pixel, red in the low byte.
vint pack(vint r, vint g, vint b) {
    return r | simd::shift_left<8>(g) | simd::shift_left<16>(b) | vint(int32_t(kOpaque));
}

// procedural::mix32 and hash(seed, x) (y = z = 0) in lanes: the same wrapping multiplies,
// xors and logical shifts.
vint mix32(vint x) {
    x = x ^ simd::shift_right_logical<16>(x);
    x = x * vint(int32_t(0x7feb352dU));
    x = x ^ simd::shift_right_logical<15>(x);
    x = x * vint(int32_t(0x846ca68bU));
    return x ^ simd::shift_right_logical<16>(x);
}
vint id_colour_lanes(vint ids) {
    // hash(seed, x, 0, 0): mix32 of the seed, then of h ^ x, then twice of h ^ 0.
    const vint seeded(int32_t(procedural::mix32(0x7e55e7aU ^ 0x9e3779b9U)));
    const vint h = mix32(mix32(mix32(seeded ^ ids)));
    // id_colour's bytes are the channels: quantise(k / 255) == k for every level k
    // (tests/stamp_shading_test, QuantisingALevelGivesItBack).
    return (h & vint(0x00FFFFFF)) | vint(int32_t(kOpaque));
}

// The normal or Phong colour of pixel centres (px, py), inputs read through `at`.
template <class At>
vint shade_lanes(ShadeMode mode, const PhongLight& phong, const At& at, vfloat px, vfloat py) {
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
    if (mode == ShadeMode::normal) {
        const vfloat half(0.5f);
        return pack(quantise(n.x * half + half), quantise(n.y * half + half), quantise(n.z * half + half));
    }
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
    return pack(quantise(albedo.x * diffuse + specular), quantise(albedo.y * diffuse + specular),
                quantise(albedo.z * diffuse + specular));
}

struct Shader {
    ShadeMode mode;
    PhongLight phong;

    // The finished pixels of kLanes lanes: triangle ids (kNoTriangle: background), window
    // depths and pixel centres; `inside`: the lanes that are pixels of the tile.
    vint shade(const pipeline::TileContext& ctx, TriangleTable& table, vint ids, vfloat depth, vfloat px,
               vfloat py, vmask inside) const {
        const vmask covered = andnot(ids == vint(int32_t(kNoTriangle)), inside);
        if (!simd::any(covered)) return kBackground;
        vint colour;
        if (mode == ShadeMode::id) {
            colour = id_colour_lanes(ids);
        } else if (mode == ShadeMode::depth) {
            const vint grey = quantise(depth);
            colour = pack(grey, grey, grey);
        } else {
            // The triangles under the covered lanes, when there are at most four (one for
            // most lanes, unless the triangles are about a pixel in size): their records as
            // constants, chosen per lane with 2 N - 1 operations per value where a gather
            // costs as much as about ten. Each is looked up before any record is read: an
            // insertion may move the records.
            uint32_t rest = simd::bits(covered);
            const auto next = [&](vmask& lanes) {
                const int32_t id = simd::lane(ids, std::countr_zero(rest));
                lanes = (ids == vint(id)) & covered;
                rest &= ~simd::bits(lanes);
                return table.find(ctx, uint32_t(id));
            };
            const auto record = [&](int32_t slot) { return table.floats() + size_t(slot) * kRecord; };
            vmask m0, m1, m2, m3;
            const int32_t s0 = next(m0);
            if (!rest) {
                colour = shade_lanes(mode, phong, Broadcast{record(s0)}, px, py);
            } else {
                const int32_t s1 = next(m1);
                if (!rest) {
                    colour = shade_lanes(mode, phong, Blend<2>{{record(s0), record(s1)}, {m1}}, px, py);
                } else {
                    const int32_t s2 = next(m2);
                    if (!rest) {
                        colour = shade_lanes(mode, phong, Blend<3>{{record(s0), record(s1), record(s2)}, {m1, m2}},
                                             px, py);
                    } else {
                        const int32_t s3 = next(m3);
                        if (!rest) {
                            colour = shade_lanes(
                                mode, phong,
                                Blend<4>{{record(s0), record(s1), record(s2), record(s3)}, {m1, m2, m3}}, px, py);
                        } else {
                            const vint slots = table.find(ctx, ids, covered);
                            colour = shade_lanes(mode, phong, Gather{table.floats(), slots * vint(kRecord)},
                                                 px, py);
                        }
                    }
                }
            }
        }
        return simd::select(covered, colour, kBackground);
    }
};

// The lanes of a stamp that lie inside the tile rectangle (stamps at the viewport's right and
// bottom edges reach past it).
vmask inside_lanes(int sx, int sy, const TileRect& rect) {
    if (sx + kStampW <= rect.x1 && sy + kStampH <= rect.y1) return vmask(true);
    return (vint(sx) + simd::stamp_x() < vint(rect.x1)) & (vint(sy) + simd::stamp_y() < vint(rect.y1));
}

// The tile from its stamp-layout buffers: kStampH stamps side by side (kLanes pixels wide)
// shaded, then stored as kStampH rows of the frame.
void shade_stamps(const Shader& shader, const pipeline::TileContext& ctx, TriangleTable& table, uint32_t* rgba8) {
    const pipeline::TileBuffers& buffers = *ctx.stamps;
    const TileRect& rect = ctx.rect;
    const size_t width = size_t(ctx.viewport->width);
    const vfloat lane_x = simd::to_float(simd::stamp_x()) + vfloat(0.5f);
    const vfloat lane_y = simd::to_float(simd::stamp_y()) + vfloat(0.5f);
    alignas(64) uint32_t group[kLanes * kStampH];
    alignas(64) uint32_t rows[kLanes * kStampH];
    for (int y = rect.y0; y < rect.y1; y += kStampH) {
        const int row_count = std::min(kStampH, rect.y1 - y);
        const vfloat py = vfloat(float(y)) + lane_y;
        for (int x = rect.x0; x < rect.x1; x += kLanes) {
            for (int s = 0; s < kStampH; ++s) {
                const int sx = x + s * kStampW;
                vint colour = kBackground;
                if (sx < rect.x1) {
                    const size_t index = buffers.index(sx - rect.x0, y - rect.y0);
                    const vint ids = vint::load(reinterpret_cast<const int32_t*>(&buffers.triangle[index]));
                    // The tiles hold depth offsets z - 1: window_depth() as the frame's buffer has it.
                    const vfloat depth = vfloat::load(&buffers.depth[index]) + vfloat(1.0f);
                    colour = shader.shade(ctx, table, ids, depth, vfloat(float(sx)) + lane_x, py,
                                          inside_lanes(sx, y, rect));
                }
                colour.store(reinterpret_cast<int32_t*>(group + s * kLanes));
            }
            uint32_t* out = rgba8 + size_t(y) * width + size_t(x);
            const int columns = std::min(kLanes, rect.x1 - x);
            if (columns == kLanes) {
                simd::store_stamp_rows(group, out, width, row_count);
            } else {
                simd::store_stamp_rows(group, rows, kLanes, kStampH);
                for (int r = 0; r < row_count; ++r)
                    std::memcpy(out + size_t(r) * width, rows + r * kLanes, size_t(columns) * sizeof(uint32_t));
            }
        }
    }
}

// The tile from its rows of the frame's visibility buffer, kLanes pixels of a row at a time.
void shade_rows(const Shader& shader, const pipeline::TileContext& ctx, TriangleTable& table, uint32_t* rgba8) {
    const TileRect& rect = ctx.rect;
    const size_t width = size_t(ctx.viewport->width);
    const vfloat lane_x = simd::to_float(simd::lane_index()) + vfloat(0.5f);
    alignas(64) int32_t ids[kLanes];
    alignas(64) float depth[kLanes];
    alignas(64) int32_t colour[kLanes];
    for (int y = rect.y0; y < rect.y1; ++y) {
        const size_t row = size_t(y - rect.y0) * ctx.stride;
        const vfloat py(float(y) + 0.5f);
        for (int x = rect.x0; x < rect.x1; x += kLanes) {
            const int n = std::min(kLanes, rect.x1 - x);
            std::memcpy(ids, ctx.triangle + row + size_t(x - rect.x0), size_t(n) * sizeof(uint32_t));
            std::memcpy(depth, ctx.depth + row + size_t(x - rect.x0), size_t(n) * sizeof(float));
            for (int k = n; k < kLanes; ++k) ids[k] = int32_t(kNoTriangle), depth[k] = 1.0f;
            shader.shade(ctx, table, vint::load(ids), vfloat::load(depth), vfloat(float(x)) + lane_x, py, vmask(true))
                .store(colour);
            std::memcpy(rgba8 + size_t(y) * width + size_t(x), colour, size_t(n) * sizeof(uint32_t));
        }
    }
}

}  // namespace

pipeline::TilePass make_stamp_shading_pass(ShadeMode mode, const Camera& camera, std::vector<uint32_t>& rgba8) {
    const Shader shader{mode, PhongLight::from(camera)};
    auto tables = std::make_shared<tbb::enumerable_thread_specific<TriangleTable>>();
    return [shader, tables, &rgba8](const pipeline::TileContext& ctx) {
        TriangleTable& table = tables->local();
        table.count = 0;
        if (ctx.stamps) shade_stamps(shader, ctx, table, rgba8.data());
        else shade_rows(shader, ctx, table, rgba8.data());
    };
}

}  // namespace tessera::shade
