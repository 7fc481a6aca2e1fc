#include "raster/shadow/shadow_map.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
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
MapPoint<F> receiver_in_map(const glm::vec3& light, const LightProjection& projection,
                            float normal_offset, float depth_bias, float size, F px, F py, F pz,
                            F nx, F ny, F nz) {
    const glm::vec3& axis = projection.axis;
    const F lx = F(light.x) - px, ly = F(light.y) - py, lz = F(light.z) - pz;  // to the light
    const F inverse_distance = F(1.0f) / sqrt_of(lx * lx + ly * ly + lz * lz);
    const F along_axis = (F(0.0f) - lx) * F(axis.x) + (F(0.0f) - ly) * F(axis.y) + (F(0.0f) - lz) * F(axis.z);
    const F texel = F(projection.texel_size) + F(projection.texel_per_depth) * max_of(along_axis, F(0.0f));
    // Slope-scaled normal offset: sin of the angle between normal and light.
    const F cosine = (nx * lx + ny * ly + nz * lz) * inverse_distance;
    const F sine = sqrt_of(max_of(F(0.0f), F(1.0f) - cosine * cosine));
    const F offset = F(normal_offset) * sine * texel;
    const F toward = F(depth_bias) * texel * inverse_distance;
    const F rx = px + nx * offset + lx * toward;
    const F ry = py + ny * offset + ly * toward;
    const F rz = pz + nz * offset + lz * toward;
    F cx, cy, cz, cw;
    pipeline::clip_position(projection.view_projection, rx, ry, rz, cx, cy, cz, cw);
    const F inverse_w = F(1.0f) / cw;
    return {(cx * inverse_w * F(0.5f) + F(0.5f)) * F(size), (F(0.5f) - cy * inverse_w * F(0.5f)) * F(size),
            cz * inverse_w * F(0.5f) + F(0.5f), cw};
}

// Whether a receiver projected into a cascade is held by it: in front of the light, within
// the depth range, and with every PCF tap inside the map (the last cascade takes receivers
// whose taps reach past its edge: those taps count as lit). Written once for float and
// simd::vfloat, as receiver_in_map.
template <class F>
auto held_by(const MapPoint<F>& m, float low, float high) {
    return (F(0.0f) < m.w) & (F(low) <= m.x) & (m.x < F(high)) & (F(low) <= m.y) & (m.y < F(high)) &
           (m.z <= F(1.0f));
}

// Cohen-Sutherland outcodes of points against the window [-limit, limit]^2 of an orthographic
// view_projection (its x and y; w is 1). A non-finite point gets no outcode.
class WindowCodes {
public:
    WindowCodes(const glm::mat4& view_projection, float limit)
        : row_x_(view_projection[0][0], view_projection[1][0], view_projection[2][0], view_projection[3][0]),
          row_y_(view_projection[0][1], view_projection[1][1], view_projection[2][1], view_projection[3][1]),
          limit_(limit) {}
    uint8_t operator()(const glm::vec3& position) const {
        const glm::vec4 p(position, 1.0f);
        const float x = glm::dot(row_x_, p), y = glm::dot(row_y_, p);
        return uint8_t((x < -limit_) | (x > limit_) << 1 | (y < -limit_) << 2 | (y > limit_) << 3);
    }

private:
    glm::vec4 row_x_, row_y_;
    float limit_;
};

// The window an orthographic cascade draws: a texel beyond the map's edge on each side, so
// that a kept triangle covers every texel centre any triangle could.
float window_limit(int size) { return 1.0f + 2.0f / float(size); }

// `out` becomes the positions of `mesh` and those of its triangles that an orthographic
// view_projection does not put entirely beyond one edge of [-limit, limit]^2 (outcodes of the
// vertices). Triangles with a non-finite vertex are kept for the rasterizer to reject. The
// depth the kept triangles leave is the depth all of them would leave: the others cover no
// texel centre.
void cull_to_window(const Mesh& mesh, const glm::mat4& view_projection, float limit, Mesh& out) {
    out.positions.assign(mesh.positions.begin(), mesh.positions.end());
    out.indices.clear();
    std::vector<uint8_t> code(mesh.positions.size());
    const WindowCodes code_of(view_projection, limit);
    for (size_t v = 0; v < code.size(); ++v) code[v] = code_of(mesh.positions[v]);
    const size_t n = mesh.vertex_count();
    for (size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
        const uint32_t a = mesh.indices[i], b = mesh.indices[i + 1], c = mesh.indices[i + 2];
        if (a < n && b < n && c < n && (code[a] & code[b] & code[c])) continue;
        out.indices.insert(out.indices.end(), {a, b, c});
    }
}

}  // namespace

ShadowMap::ShadowMap(pipeline::Rasterizer& rasterizer, const Mesh& mesh, const ShadowLight& light,
                     const ShadowMapOptions& options)
    : light_(light), options_(options) {
    check_shadow_map_settings(options);
    static_assert(pipeline::kMaxViewport == 8192, "check_shadow_map_settings's size limit");
    render(rasterizer, mesh, light, nullptr);
}

ShadowMap::ShadowMap(pipeline::Rasterizer& rasterizer, const Mesh& mesh, const ShadowLight& light,
                     const Camera& camera, const ShadowMapOptions& options)
    : light_(light), options_(options) {
    check_shadow_map_settings(options);
    render(rasterizer, mesh, light, &camera);
}

void ShadowMap::render(pipeline::Rasterizer& rasterizer, const Mesh& mesh, const ShadowLight& light,
                       const Camera* camera) {
    light_ = light;
    const Bounds bounds = mesh_bounds(mesh);
    const int size = options_.resolution;
    std::vector<Sphere> spheres;
    splits_.clear();
    if (camera) {
        const auto [near, far] = shadowed_depths(*camera, bounds);
        splits_ = cascade_splits(near, far, options_.cascades, options_.split_blend);
        for (int c = 0; c < options_.cascades; ++c)
            spheres.push_back(slice_sphere(*camera, splits_[size_t(c)], splits_[size_t(c) + 1]));
    } else {
        spheres.push_back(bounds_sphere(bounds));
    }
    // What moved since the last render, vertex by vertex (bitwise: a NaN that stays is no
    // move); with other triangles, everything did.
    const bool same_triangles = rendered_mesh_.positions.size() == mesh.positions.size() &&
                                rendered_mesh_.indices == mesh.indices;
    bool any_moved = false;
    if (same_triangles) {
        moved_.resize(mesh.vertex_count());
        for (size_t v = 0; v < moved_.size(); ++v) {
            moved_[v] = std::memcmp(&mesh.positions[v], &rendered_mesh_.positions[v], sizeof(glm::vec3)) != 0;
            any_moved |= moved_[v] != 0;
        }
    }
    cascades_.resize(spheres.size());
    cascades_rendered_ = 0;
    pipeline::RasterOptions raster;
    raster.cull = pipeline::CullMode::none;  // both faces of a surface cast shadows
    raster.depth_only = true;
    for (size_t c = 0; c < spheres.size(); ++c) {
        Cascade& cascade = cascades_[c];
        const LightProjection projection = light.distant ? fit_distant_light(light.position, spheres[c], bounds, size)
                                                         : fit_point_light(light.position, spheres[c], bounds, size);
        // The depth is a function of the view_projection, the size and the triangles alone
        // (the rasterizer's result does not depend on anything else).
        const bool same_view = cascade.rendered && same_triangles && cascade.depth.width == size &&
                               std::memcmp(&projection.view_projection, &cascade.projection.view_projection,
                                           sizeof(glm::mat4)) == 0;
        cascade.projection = projection;
        if (same_view && (!any_moved || !moved_in_window(mesh, projection, light.distant, moved_))) continue;
        cascade.rendered = false;  // until the render below has succeeded
        const Mesh* drawn = &mesh;
        if (light.distant) {
            cull_to_window(mesh, projection.view_projection, window_limit(size), culled_);
            drawn = &culled_;
        }
        rasterizer.render(*drawn, projection.view_projection, pipeline::Viewport(size, size), raster, cascade.depth);
        cascade.rendered = true;
        ++cascades_rendered_;
    }
    if (!same_triangles) rendered_mesh_.indices.assign(mesh.indices.begin(), mesh.indices.end());
    if (!same_triangles || any_moved) rendered_mesh_.positions.assign(mesh.positions.begin(), mesh.positions.end());
}

bool ShadowMap::moved_in_window(const Mesh& mesh, const LightProjection& projection, bool orthographic,
                                const std::vector<uint8_t>& moved) const {
    // A perspective cascade draws the whole mesh: any move may show in it.
    if (!orthographic) return true;
    const WindowCodes code(projection.view_projection, window_limit(options_.resolution));
    const std::vector<glm::vec3>& before = rendered_mesh_.positions;
    const std::vector<glm::vec3>& now = mesh.positions;
    const size_t n = mesh.vertex_count();
    for (size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
        const uint32_t a = mesh.indices[i], b = mesh.indices[i + 1], c = mesh.indices[i + 2];
        if (a >= n || b >= n || c >= n || !(moved[a] | moved[b] | moved[c])) continue;
        // Culled (cull_to_window) both before and now: it covered no texel of this window.
        if (!(code(before[a]) & code(before[b]) & code(before[c])) || !(code(now[a]) & code(now[b]) & code(now[c])))
            return true;
    }
    return false;
}

template <bool kMajority>
int ShadowMap::count_lit(const glm::vec3& position, const glm::vec3& normal, int* cascade) const {
    const int r = options_.pcf_radius, taps = (2 * r + 1) * (2 * r + 1);
    const int size = options_.resolution;
    const int last = cascade_count() - 1;
    for (int c = 0; c <= last; ++c) {
        const MapPoint<float> m = receiver_in_map(light_.position, cascades_[size_t(c)].projection,
                                                  options_.normal_offset, options_.depth_bias, float(size),
                                                  position.x, position.y, position.z, normal.x, normal.y,
                                                  normal.z);
        const float low = c == last ? 0.0f : float(r), high = float(size) - low;
        if (!held_by(m, low, high)) continue;
        if (cascade) *cascade = c;
        const int cx = int(m.x), cy = int(m.y);
        // Taps beyond the map's edge see nothing stored: lit. Count the dark ones inside.
        const int x0 = std::max(cx - r, 0), x1 = std::min(cx + r, size - 1);
        const int y0 = std::max(cy - r, 0), y1 = std::min(cy + r, size - 1);
        const int most_dark = taps / 2;  // lit() needs at least taps - taps/2 lit
        const float* depth = cascades_[size_t(c)].depth.depth.data();
        int dark = 0, seen = 0;
        for (int ty = y0; ty <= y1; ++ty) {
            const float* row = depth + size_t(ty) * size_t(size);
            for (int tx = x0; tx <= x1; ++tx) {
                dark += m.z > row[tx];
                ++seen;
            }
            if (kMajority && (dark > most_dark || seen - dark >= taps - most_dark)) break;
        }
        return taps - dark - (kMajority ? (y1 - y0 + 1) * (x1 - x0 + 1) - seen : 0);
    }
    if (cascade) *cascade = cascade_count();
    return taps;  // outside every cascade
}

float ShadowMap::lit_fraction(const glm::vec3& position, const glm::vec3& normal) const {
    const int taps = (2 * options_.pcf_radius + 1) * (2 * options_.pcf_radius + 1);
    return float(count_lit<false>(position, normal)) / float(taps);
}

bool ShadowMap::lit(const glm::vec3& position, const glm::vec3& normal) const {
    const int taps = (2 * options_.pcf_radius + 1) * (2 * options_.pcf_radius + 1);
    return count_lit<true>(position, normal) >= taps - taps / 2;
}

int ShadowMap::cascade_of(const glm::vec3& position, const glm::vec3& normal) const {
    int cascade = 0;
    count_lit<true>(position, normal, &cascade);
    return cascade;
}

void ShadowMap::mark_lit_reference(const SurfacePoints& points, uint8_t bit,
                                   std::span<uint8_t> visible) const {
    for (size_t i = 0; i < points.size(); ++i)
        if (faces_light(points.position[i], points.normal[i], light_.position) &&
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
    const int last = cascade_count() - 1;
    const glm::vec3& light = light_.position;
    const float* position = &points.position[0].x;
    const float* normal = &points.normal[0].x;
    static_assert(sizeof(glm::vec3) == 3 * sizeof(float));
    const vint zero(0), limit(size), last_point(int32_t(n - 1));
    for (size_t first = 0; first < n; first += simd::kLanes) {
        // Lanes past the end repeat the last point; their answers are not stored.
        vint index = vint(int32_t(first)) + simd::lane_index();
        index = simd::select(index < last_point, index, last_point);
        const vint offset = index * vint(3);
        const vfloat px = simd::gather(position, offset), py = simd::gather(position + 1, offset),
                     pz = simd::gather(position + 2, offset);
        const vfloat nx = simd::gather(normal, offset), ny = simd::gather(normal + 1, offset),
                     nz = simd::gather(normal + 2, offset);
        const vmask faces = faces_light(px, py, pz, nx, ny, nz, light);
        if (!simd::any(faces)) continue;
        vmask pending = faces, lit(false);
        for (int c = 0; c <= last && simd::any(pending); ++c) {
            const MapPoint<vfloat> m = receiver_in_map(light, cascades_[size_t(c)].projection,
                                                       options_.normal_offset, options_.depth_bias,
                                                       float(size), px, py, pz, nx, ny, nz);
            const float low = c == last ? 0.0f : float(r), high = float(size) - low;
            const vmask here = pending & held_by(m, low, high);
            if (!simd::any(here)) continue;
            const float* depth = cascades_[size_t(c)].depth.depth.data();
            // int(x) of count_lit: x >= 0 where held, so floor is truncation; other lanes
            // read texel 0.
            const vint cx = simd::select(here, simd::round_to_int(simd::floor(m.x)), zero);
            const vint cy = simd::select(here, simd::round_to_int(simd::floor(m.y)), zero);
            // lit(): at least taps - taps/2 of the taps lit, i.e. fewer than `dark_needed`
            // dark. As count_lit<true>, the taps stop once every lane's majority is known
            // (both counts are monotone): inside a lit or a shadowed region, after
            // dark_needed of them. Gathers are most of the lookup's cost.
            const int dark_needed = taps / 2 + 1, lit_needed = taps - taps / 2;
            vint dark(0);
            int read = 0;
            for (int dy = -r; dy <= r; ++dy) {
                const vint ty = cy + vint(dy);
                const vmask row_in = (ty >= zero) & (ty < limit);  // taps beyond the edge are lit
                int dx = -r;
                for (; dx <= r; ++dx) {
                    const vint tx = cx + vint(dx);
                    const vmask in = row_in & (tx >= zero) & (tx < limit);
                    const vint texel = simd::select(in, ty * limit + tx, zero);
                    const vmask shadowed = in & (simd::gather(depth, texel) < m.z);
                    dark = dark + simd::select(shadowed, vint(1), zero);
                    if (++read < lit_needed) continue;
                    const vmask decided = (dark >= vint(dark_needed)) | (vint(read) - dark >= vint(lit_needed));
                    if (!simd::any(simd::andnot(decided, here))) break;
                }
                if (dx <= r) break;
            }
            lit = lit | (here & (dark < vint(dark_needed)));
            pending = simd::andnot(here, pending);
        }
        lit = lit | pending;  // outside every cascade
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
