#include "raster/shadow/shadow_map.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "raster/core/camera.h"
#include "raster/simd/simd.h"
#include "raster/pipeline/vertex_stage.h"
#include "raster/pipeline/fixed_point.h"
#include "raster/pipeline/viewport.h"

namespace tessera::shadow {
namespace {

struct Bounds {
    glm::vec3 lo{std::numeric_limits<float>::infinity()};
    glm::vec3 hi{-std::numeric_limits<float>::infinity()};
};

// Bounds of the finite vertices (min/max: the same whatever the split).
Bounds mesh_bounds(const Mesh& mesh) {
    return tbb::parallel_reduce(
        tbb::blocked_range<size_t>(0, mesh.vertex_count(), 1 << 15), Bounds{},
        [&](const tbb::blocked_range<size_t>& range, Bounds b) {
            for (size_t v = range.begin(); v != range.end(); ++v) {
                const glm::vec3& p = mesh.positions[v];
                if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) continue;
                b.lo = glm::min(b.lo, p);
                b.hi = glm::max(b.hi, p);
            }
            return b;
        },
        [](Bounds a, const Bounds& b) {
            a.lo = glm::min(a.lo, b.lo);
            a.hi = glm::max(a.hi, b.hi);
            return a;
        });
}

// Overloads that let receiver_in_map run on one float or on simd lanes with identical
// results (simd::max is `a > b ? a : b` per lane, NaN included).
float max_of(float a, float b) { return a > b ? a : b; }
simd::vfloat max_of(simd::vfloat a, simd::vfloat b) { return simd::max(a, b); }
float sqrt_of(float a) { return std::sqrt(a); }
simd::vfloat sqrt_of(simd::vfloat a) { return simd::sqrt(a); }

// A receiver's position in the map: texel coordinates x, y (pixel units, rows top to bottom),
// window depth z, and clip w (the point is in front of the light where w > 0).
template <class F>
struct MapPoint {
    F x, y, z, w;
};

// The biased receiver (shadow_map.h) of the surface point p with unit normal n, projected
// into the map. Written once for float and simd::vfloat: every operation is an IEEE single
// operation in a fixed order (no contraction: the build uses -ffp-contract=off), so the
// scalar lookup and the SIMD one agree to the bit.
template <class F>
MapPoint<F> receiver_in_map(const glm::vec3& light, const glm::vec3& axis, const glm::mat4& vp,
                            float texel_per_depth, float normal_offset, float depth_bias,
                            float size, F px, F py, F pz, F nx, F ny, F nz) {
    const F lx = F(light.x) - px, ly = F(light.y) - py, lz = F(light.z) - pz;  // to the light
    const F inverse_distance = F(1.0f) / sqrt_of(lx * lx + ly * ly + lz * lz);
    const F along_axis = (F(0.0f) - lx) * F(axis.x) + (F(0.0f) - ly) * F(axis.y) + (F(0.0f) - lz) * F(axis.z);
    const F texel = F(texel_per_depth) * max_of(along_axis, F(0.0f));
    // Slope-scaled normal offset: sin of the angle between normal and light.
    const F cosine = (nx * lx + ny * ly + nz * lz) * inverse_distance;
    const F sine = sqrt_of(max_of(F(0.0f), F(1.0f) - cosine * cosine));
    const F offset = F(normal_offset) * sine * texel;
    const F toward = F(depth_bias) * texel * inverse_distance;
    const F rx = px + nx * offset + lx * toward;
    const F ry = py + ny * offset + ly * toward;
    const F rz = pz + nz * offset + lz * toward;
    F cx, cy, cz, cw;
    pipeline::clip_position(vp, rx, ry, rz, cx, cy, cz, cw);
    const F inverse_w = F(1.0f) / cw;
    return {(cx * inverse_w * F(0.5f) + F(0.5f)) * F(size), (F(0.5f) - cy * inverse_w * F(0.5f)) * F(size),
            cz * inverse_w * F(0.5f) + F(0.5f), cw};
}

}  // namespace

ShadowMap::ShadowMap(pipeline::Rasterizer& rasterizer, const Mesh& mesh, const glm::vec3& light,
                     const ShadowMapOptions& options)
    : light_(light), options_(options) {
    if (options.resolution < 16 || options.resolution > pipeline::kMaxViewport)
        throw std::invalid_argument("shadow map resolution " + std::to_string(options.resolution) +
                                    " is outside 16 .. " + std::to_string(pipeline::kMaxViewport));
    if (options.pcf_radius < 0 || options.pcf_radius > 8)
        throw std::invalid_argument("PCF radius " + std::to_string(options.pcf_radius) +
                                    " is outside 0 .. 8");
    if (!(options.normal_offset >= 0.0f) || !(options.depth_bias >= 0.0f))
        throw std::invalid_argument("shadow bias must be zero or positive");
    render(rasterizer, mesh, light);
}

void ShadowMap::render(pipeline::Rasterizer& rasterizer, const Mesh& mesh, const glm::vec3& light) {
    light_ = light;
    const Bounds bounds = mesh_bounds(mesh);
    const bool empty = !(bounds.lo.x <= bounds.hi.x);
    const glm::vec3 centre = empty ? light + glm::vec3(0, 0, -1) : 0.5f * (bounds.lo + bounds.hi);
    const float radius = empty ? 1.0f : std::max(0.5f * glm::length(bounds.hi - bounds.lo), 1e-6f);
    float distance = glm::length(centre - light);
    Camera camera;
    camera.eye = light;
    // Looking at the centre; from inside the sphere (or on it) any direction will do.
    camera.lookat = distance > 1e-6f * radius ? centre : light + glm::vec3(0, -1, 0);
    distance = std::max(distance, 1e-6f * radius);
    axis_ = glm::normalize(camera.lookat - light);
    camera.up = std::abs(axis_.y) > 0.99f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
    camera.aspect = 1.0f;
    const bool outside = distance > 1.01f * radius;
    camera.fovy_deg = outside ? glm::degrees(2.0f * std::asin(radius / distance)) * 1.02f : 120.0f;
    // Near at the sphere's closest point, but not so close that depth precision collapses.
    camera.far = distance + radius;
    camera.near = std::max(distance - radius, camera.far * 1e-3f);
    view_projection_ = camera.view_projection();
    texel_per_depth_ =
        2.0f * std::tan(glm::radians(camera.fovy_deg) * 0.5f) / float(options_.resolution);
    pipeline::RasterOptions raster;
    raster.cull = pipeline::CullMode::none;  // both faces of a surface cast shadows
    raster.depth_only = true;
    rasterizer.render(mesh, view_projection_, pipeline::Viewport(options_.resolution, options_.resolution),
                      raster, depth_);
}

template <bool kMajority>
int ShadowMap::count_lit(const glm::vec3& position, const glm::vec3& normal) const {
    const int r = options_.pcf_radius, taps = (2 * r + 1) * (2 * r + 1);
    const int size = options_.resolution;
    const MapPoint<float> m = receiver_in_map(light_, axis_, view_projection_, texel_per_depth_,
                                              options_.normal_offset, options_.depth_bias, float(size),
                                              position.x, position.y, position.z, normal.x, normal.y,
                                              normal.z);
    if (!(m.w > 0.0f)) return taps;  // behind the light's view: outside the map
    const float x = m.x, y = m.y, z = m.z;
    if (!(x >= 0.0f && x < float(size) && y >= 0.0f && y < float(size))) return taps;
    const int cx = int(x), cy = int(y);
    // Taps beyond the map's edge see nothing stored: lit. Count the dark ones inside.
    const int x0 = std::max(cx - r, 0), x1 = std::min(cx + r, size - 1);
    const int y0 = std::max(cy - r, 0), y1 = std::min(cy + r, size - 1);
    const int most_dark = taps / 2;  // lit() needs at least taps - taps/2 lit
    int dark = 0, seen = 0;
    for (int ty = y0; ty <= y1; ++ty) {
        const float* row = depth_.depth.data() + size_t(ty) * size_t(size);
        for (int tx = x0; tx <= x1; ++tx) {
            dark += z > row[tx];
            ++seen;
        }
        if (kMajority && (dark > most_dark || seen - dark >= taps - most_dark)) break;
    }
    return taps - dark - (kMajority ? (y1 - y0 + 1) * (x1 - x0 + 1) - seen : 0);
}

float ShadowMap::lit_fraction(const glm::vec3& position, const glm::vec3& normal) const {
    const int taps = (2 * options_.pcf_radius + 1) * (2 * options_.pcf_radius + 1);
    return float(count_lit<false>(position, normal)) / float(taps);
}

bool ShadowMap::lit(const glm::vec3& position, const glm::vec3& normal) const {
    const int taps = (2 * options_.pcf_radius + 1) * (2 * options_.pcf_radius + 1);
    return count_lit<true>(position, normal) >= taps - taps / 2;
}

void ShadowMap::mark_lit_reference(const SurfacePoints& points, uint8_t bit,
                                   std::span<uint8_t> visible) const {
    for (size_t i = 0; i < points.size(); ++i)
        if (faces_light(points.position[i], points.normal[i], light_) &&
            lit(points.position[i], points.normal[i]))
            visible[i] |= bit;
}

void ShadowMap::mark_lit(const SurfacePoints& points, uint8_t bit, std::span<uint8_t> visible) const {
    using simd::vfloat;
    using simd::vint;
    using simd::vmask;
    const size_t n = points.size();
    if (n == 0) return;
    const int r = options_.pcf_radius, taps = (2 * r + 1) * (2 * r + 1);
    const int size = options_.resolution;
    const float* depth = depth_.depth.data();
    const float* position = &points.position[0].x;
    const float* normal = &points.normal[0].x;
    static_assert(sizeof(glm::vec3) == 3 * sizeof(float));
    const vint zero(0), limit(size), last(int32_t(n - 1));
    const vfloat fsize = vfloat(float(size));
    for (size_t first = 0; first < n; first += simd::kLanes) {
        // Lanes past the end repeat the last point; their answers are not stored.
        vint index = vint(int32_t(first)) + simd::lane_index();
        index = simd::select(index < last, index, last);
        const vint offset = index * vint(3);
        const vfloat px = simd::gather(position, offset), py = simd::gather(position + 1, offset),
                     pz = simd::gather(position + 2, offset);
        const vfloat nx = simd::gather(normal, offset), ny = simd::gather(normal + 1, offset),
                     nz = simd::gather(normal + 2, offset);
        // faces_light(): dot(normal, light - position) > 0, in glm's order ((x + y) + z).
        const vfloat facing = nx * (vfloat(light_.x) - px) + ny * (vfloat(light_.y) - py) +
                              nz * (vfloat(light_.z) - pz);
        const vmask faces = vfloat(0.0f) < facing;
        if (!simd::any(faces)) continue;
        const MapPoint<vfloat> m = receiver_in_map(light_, axis_, view_projection_, texel_per_depth_,
                                                   options_.normal_offset, options_.depth_bias,
                                                   float(size), px, py, pz, nx, ny, nz);
        const vmask inside = (vfloat(0.0f) < m.w) & (vfloat(0.0f) <= m.x) & (m.x < fsize) &
                             (vfloat(0.0f) <= m.y) & (m.y < fsize);
        // int(x) of count_lit: x >= 0 inside, so floor is truncation; other lanes read texel 0.
        const vint cx = simd::select(inside, simd::round_to_int(simd::floor(m.x)), zero);
        const vint cy = simd::select(inside, simd::round_to_int(simd::floor(m.y)), zero);
        vint dark(0);
        for (int dy = -r; dy <= r; ++dy) {
            const vint ty = cy + vint(dy);
            const vmask row_in = (ty >= zero) & (ty < limit);  // taps beyond the edge are lit
            for (int dx = -r; dx <= r; ++dx) {
                const vint tx = cx + vint(dx);
                const vmask in = row_in & (tx >= zero) & (tx < limit);
                const vint texel = simd::select(in, ty * limit + tx, zero);
                const vmask shadowed = in & (simd::gather(depth, texel) < m.z);
                dark = dark + simd::select(shadowed, vint(1), zero);
            }
        }
        // lit(): at least taps - taps/2 of the taps lit, i.e. at most taps/2 dark.
        const vmask lit = simd::andnot(inside, vmask(true)) | (dark < vint(taps / 2 + 1));
        const size_t count = std::min<size_t>(simd::kLanes, n - first);
        for (uint32_t bits = simd::bits(faces & lit); bits; bits &= bits - 1) {
            const size_t lane = size_t(std::countr_zero(bits));
            if (lane < count) visible[first + lane] |= bit;
        }
    }
}

LightTest shadow_map_test(std::span<const ShadowMap> maps) {
    return [maps](const SurfacePoints& points, std::span<const glm::vec3> lights,
                  std::span<uint8_t> visible) {
        if (maps.size() != lights.size())
            throw std::invalid_argument("one shadow map per light is needed");
        for (size_t l = 0; l < lights.size(); ++l) maps[l].mark_lit(points, uint8_t(1u << l), visible);
    };
}

}  // namespace tessera::shadow
