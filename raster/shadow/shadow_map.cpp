#include "raster/shadow/shadow_map.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "raster/camera.h"
#include "raster/fixed_point.h"
#include "raster/viewport.h"

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

}  // namespace

ShadowMap::ShadowMap(Rasterizer& rasterizer, const Mesh& mesh, const glm::vec3& light,
                     const ShadowMapOptions& options)
    : light_(light), options_(options) {
    if (options.resolution < 16 || options.resolution > kMaxViewport)
        throw std::invalid_argument("shadow map resolution " + std::to_string(options.resolution) +
                                    " is outside 16 .. " + std::to_string(kMaxViewport));
    if (options.pcf_radius < 0 || options.pcf_radius > 8)
        throw std::invalid_argument("PCF radius " + std::to_string(options.pcf_radius) +
                                    " is outside 0 .. 8");
    if (!(options.normal_offset >= 0.0f) || !(options.depth_bias >= 0.0f))
        throw std::invalid_argument("shadow bias must be zero or positive");
    render(rasterizer, mesh, light);
}

void ShadowMap::render(Rasterizer& rasterizer, const Mesh& mesh, const glm::vec3& light) {
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
    RasterOptions raster;
    raster.cull = CullMode::none;  // both faces of a surface cast shadows
    rasterizer.render(mesh, view_projection_, Viewport(options_.resolution, options_.resolution),
                      raster, depth_);
}

template <bool kMajority>
int ShadowMap::count_lit(const glm::vec3& position, const glm::vec3& normal) const {
    const int r = options_.pcf_radius, taps = (2 * r + 1) * (2 * r + 1);
    const glm::vec3 to_light = light_ - position;
    const float inverse_distance = 1.0f / std::sqrt(glm::dot(to_light, to_light));
    const float texel = texel_per_depth_ * std::max(glm::dot(-to_light, axis_), 0.0f);
    // Slope-scaled normal offset (shadow_map.h): sin of the angle between normal and light.
    const float cosine = glm::dot(normal, to_light) * inverse_distance;
    const float sine = std::sqrt(std::max(0.0f, 1.0f - cosine * cosine));
    const glm::vec3 receiver = position + normal * (options_.normal_offset * sine * texel) +
                               to_light * (options_.depth_bias * texel * inverse_distance);
    const glm::vec4 clip = view_projection_ * glm::vec4(receiver, 1.0f);
    if (!(clip.w > 0.0f)) return taps;  // behind the light's view: outside the map
    const int size = options_.resolution;
    const float inverse_w = 1.0f / clip.w;
    const float x = (clip.x * inverse_w * 0.5f + 0.5f) * float(size);
    const float y = (0.5f - clip.y * inverse_w * 0.5f) * float(size);
    const float z = clip.z * inverse_w * 0.5f + 0.5f;
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

LightTest shadow_map_test(std::span<const ShadowMap> maps) {
    return [maps](const SurfacePoints& points, std::span<const glm::vec3> lights,
                  std::span<uint8_t> visible) {
        if (maps.size() != lights.size())
            throw std::invalid_argument("one shadow map per light is needed");
        for (size_t l = 0; l < lights.size(); ++l)
            for (size_t i = 0; i < points.size(); ++i)
                if (faces_light(points.position[i], points.normal[i], lights[l]) &&
                    maps[l].lit(points.position[i], points.normal[i]))
                    visible[i] |= uint8_t(1u << l);
    };
}

}  // namespace tessera::shadow
