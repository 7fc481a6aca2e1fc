#include "raster/geometry/surfaces.h"

#include <glm/gtc/constants.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace tessera::geometry {
namespace {

constexpr float kPi = glm::pi<float>();
constexpr float kTwoPi = 2.0f * glm::pi<float>();

}  // namespace

SurfaceFunction sphere_surface(glm::vec3 center, float radius) {
    return ellipsoid_surface(center, glm::vec3(radius));
}

SurfaceFunction ellipsoid_surface(glm::vec3 center, glm::vec3 radii) {
    if (!(radii.x > 0.0f && radii.y > 0.0f && radii.z > 0.0f))
        throw std::invalid_argument("ellipsoid radii must be positive");
    return [center, radii](float u, float v) {
        const float cu = std::cos(kTwoPi * u), su = std::sin(kTwoPi * u);
        const float cv = std::cos(kPi * v), sv = std::sin(kPi * v);
        const glm::vec3 n(cu * sv, su * sv, cv);  // the unit-sphere normal
        SurfacePoint p;
        p.position = center + radii * n;
        p.dpdu = radii * glm::vec3(-kTwoPi * su * sv, kTwoPi * cu * sv, 0.0f);
        p.dpdv = radii * glm::vec3(kPi * cu * cv, kPi * su * cv, -kPi * sv);
        p.normal = n / radii;  // gradient of x^2/a^2 + y^2/b^2 + z^2/c^2 (up to a factor 2)
        return p;
    };
}

SurfaceFunction torus_surface(float major, float minor) {
    if (!(minor > 0.0f && major > minor))
        throw std::invalid_argument("torus needs major > minor > 0");
    return [major, minor](float u, float v) {
        const float ct = std::cos(kTwoPi * u), st = std::sin(kTwoPi * u);
        const float cp = std::cos(kTwoPi * v), sp = std::sin(kTwoPi * v);
        const float ring = major + minor * cp;
        SurfacePoint p;
        p.position = {ring * ct, ring * st, minor * sp};
        p.dpdu = {-kTwoPi * ring * st, kTwoPi * ring * ct, 0.0f};
        p.dpdv = {-kTwoPi * minor * sp * ct, -kTwoPi * minor * sp * st, kTwoPi * minor * cp};
        p.normal = {cp * ct, cp * st, sp};  // outward: from the tube's centre line
        return p;
    };
}

SurfaceFunction flag_surface(float width, float height, float depth, float waves, float phase) {
    if (!(width > 0.0f && height > 0.0f))
        throw std::invalid_argument("flag width and height must be positive");
    return [=](float u, float v) {
        const float angle = waves * kPi * u + phase;
        SurfacePoint p;
        p.position = {u * width, v * height, std::sin(angle) * depth};
        p.dpdu = {width, 0.0f, waves * kPi * std::cos(angle) * depth};
        p.dpdv = {0.0f, height, 0.0f};
        p.normal = {-waves * kPi * std::cos(angle) * depth, 0.0f, width};
        return p;
    };
}

SurfaceFunction heightfield_surface(std::span<const float> heights, int columns, int rows,
                                    glm::vec2 size, float height_scale) {
    if (columns < 2 || rows < 2 || heights.size() != size_t(columns) * size_t(rows))
        throw std::invalid_argument("heightfield of " + std::to_string(columns) + " x " +
                                    std::to_string(rows) + " samples needs at least 2 x 2 and " +
                                    "exactly that many heights, got " +
                                    std::to_string(heights.size()));
    if (!(size.x > 0.0f && size.y > 0.0f))
        throw std::invalid_argument("heightfield size must be positive");
    return [=](float u, float v) {
        // u runs along +x, v along +z (row j at z = (j / (rows - 1) - 0.5) * size.z); then
        // dr/dv x dr/du points up (+y), and tessellate() winds the triangles to face it.
        const int i = std::clamp(int(std::lround(u * float(columns - 1))), 0, columns - 1);
        const int j = std::clamp(int(std::lround(v * float(rows - 1))), 0, rows - 1);
        const auto h = [&](int x, int z) {
            x = std::clamp(x, 0, columns - 1);
            z = std::clamp(z, 0, rows - 1);
            return heights[size_t(z) * size_t(columns) + size_t(x)] * height_scale;
        };
        // Central differences in parameter units (one-sided at the border).
        const int i0 = std::max(i - 1, 0), i1 = std::min(i + 1, columns - 1);
        const int j0 = std::max(j - 1, 0), j1 = std::min(j + 1, rows - 1);
        const float dh_du = (h(i1, j) - h(i0, j)) / (float(i1 - i0) / float(columns - 1));
        const float dh_dv = (h(i, j1) - h(i, j0)) / (float(j1 - j0) / float(rows - 1));
        SurfacePoint p;
        p.position = {(u - 0.5f) * size.x, h(i, j), (v - 0.5f) * size.y};
        p.dpdu = {size.x, dh_du, 0.0f};
        p.dpdv = {0.0f, dh_dv, size.y};
        p.normal = glm::cross(p.dpdv, p.dpdu);  // (-dh/dx, 1, -dh/dz) * size.x * size.y
        return p;
    };
}

}  // namespace tessera::geometry
