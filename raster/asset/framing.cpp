#include "raster/asset/framing.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace tessera::asset {

glm::vec3 framing_direction() {
    const float azimuth = glm::radians(30.0f), elevation = glm::radians(20.0f);
    return {std::sin(azimuth) * std::cos(elevation), std::sin(elevation), std::cos(azimuth) * std::cos(elevation)};
}

Camera frame_box(glm::vec3 lower, glm::vec3 upper, float aspect, float fovy_deg) {
    for (int k = 0; k < 3; ++k)
        if (!std::isfinite(lower[k]) || !std::isfinite(upper[k]))
            throw std::invalid_argument("cannot frame a box with non-finite bounds");
    if (!(fovy_deg > 0.0f && fovy_deg < 180.0f) || !(aspect > 0.0f))
        throw std::invalid_argument("cannot frame with a field of view outside (0, 180) degrees");
    // Double precision: a box far from the origin must not lose its size to rounding. A box of
    // no size (one point) is framed as a tiny one around it.
    const glm::dvec3 centre = 0.5 * (glm::dvec3(lower) + glm::dvec3(upper));
    const double scale = std::max({1.0, std::abs(centre.x), std::abs(centre.y), std::abs(centre.z)});
    const glm::dvec3 half = glm::max(0.5 * (glm::dvec3(upper) - glm::dvec3(lower)), glm::dvec3(1e-6 * scale));
    // The view's frame: `back` towards the eye, right, up (+y up; the direction is never vertical).
    const glm::dvec3 back(framing_direction());
    const glm::dvec3 right = glm::normalize(glm::cross(glm::dvec3(0, 1, 0), back));
    const glm::dvec3 up = glm::cross(back, right);
    // With a 5% margin on each side, every corner k at (x, y) in the view plane and z towards
    // the eye must satisfy |x| <= (d - z) tan(half_x) and |y| <= (d - z) tan(half_y) for an eye
    // at distance d from the centre: the smallest such d frames the box tightly.
    const double tan_y = std::tan(glm::radians(double(fovy_deg)) * 0.5) * 0.95;
    const double tan_x = tan_y * double(aspect);
    double distance = 0.0, nearest = 1e300, farthest = -1e300;
    glm::dvec3 corners[8];
    for (int k = 0; k < 8; ++k) {
        corners[k] = glm::dvec3(k & 1 ? half.x : -half.x, k & 2 ? half.y : -half.y, k & 4 ? half.z : -half.z);
        const double x = glm::dot(corners[k], right), y = glm::dot(corners[k], up), z = glm::dot(corners[k], back);
        distance = std::max(distance, z + std::max(std::abs(x) / tan_x, std::abs(y) / tan_y));
    }
    // Never inside the box's bounding sphere, so that near stays a fair fraction of far.
    distance = std::max(distance, 1.1 * glm::length(half));
    for (const glm::dvec3& c : corners) {
        const double depth = distance - glm::dot(c, back);
        nearest = std::min(nearest, depth);
        farthest = std::max(farthest, depth);
    }

    Camera camera;
    camera.lookat = glm::vec3(centre);
    camera.eye = glm::vec3(centre + back * distance);
    camera.up = {0.0f, 1.0f, 0.0f};
    camera.fovy_deg = fovy_deg;
    camera.aspect = aspect;
    // Nearest and farthest corner depths, 1% beyond, keep the box off the clip planes.
    camera.near = float(nearest * 0.99);
    camera.far = float(farthest * 1.01);
    return camera;
}

std::string camera_flags(const Camera& c) {
    char text[512];
    std::snprintf(text, sizeof text,
                  "--eye %.9g,%.9g,%.9g --lookat %.9g,%.9g,%.9g --up %.9g,%.9g,%.9g --fov %.9g --near %.9g --far %.9g",
                  c.eye.x, c.eye.y, c.eye.z, c.lookat.x, c.lookat.y, c.lookat.z, c.up.x, c.up.y, c.up.z, c.fovy_deg,
                  c.near, c.far);
    return text;
}

}  // namespace tessera::asset
