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
        2.0f * std::tan(glm::radians(camera.fovy_deg) * 0.5f) / float(options.resolution);
    RasterOptions raster;
    raster.cull = CullMode::none;  // both faces of a surface cast shadows
    rasterizer.render(mesh, view_projection_, Viewport(options.resolution, options.resolution),
                      raster, depth_);
}

float ShadowMap::lit_fraction(const glm::vec3& position, const glm::vec3& normal) const {
    const glm::vec3 to_light = light_ - position;
    const float distance = glm::length(to_light);
    const float texel = texel_per_depth_ * std::max(glm::dot(position - light_, axis_), 0.0f);
    // Slope-scaled normal offset (shadow_map.h): sin of the angle between normal and light.
    const float cosine = glm::dot(normal, to_light) / distance;
    const float sine = std::sqrt(std::max(0.0f, 1.0f - cosine * cosine));
    const glm::vec3 receiver = position + normal * (options_.normal_offset * sine * texel) +
                               to_light * (options_.depth_bias * texel / distance);
    const glm::vec4 clip = view_projection_ * glm::vec4(receiver, 1.0f);
    if (!(clip.w > 0.0f)) return 1.0f;  // behind the light's view: outside the map
    const int size = options_.resolution;
    const float x = (clip.x / clip.w * 0.5f + 0.5f) * float(size);
    const float y = (0.5f - clip.y / clip.w * 0.5f) * float(size);
    const float z = clip.z / clip.w * 0.5f + 0.5f;
    if (!(x >= 0.0f && x < float(size) && y >= 0.0f && y < float(size))) return 1.0f;
    const int cx = int(x), cy = int(y), r = options_.pcf_radius;
    int lit = 0;
    for (int ty = cy - r; ty <= cy + r; ++ty)
        for (int tx = cx - r; tx <= cx + r; ++tx) {
            // Taps beyond the map's edge see nothing stored: lit.
            if (tx < 0 || ty < 0 || tx >= size || ty >= size ||
                z <= depth_.depth[size_t(ty) * size_t(size) + size_t(tx)])
                ++lit;
        }
    return float(lit) / float((2 * r + 1) * (2 * r + 1));
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
