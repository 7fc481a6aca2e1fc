#include "raster/geometry/snake.h"

#include <glm/gtc/constants.hpp>

#include <array>
#include <cmath>

#include "raster/geometry/bezier.h"
#include "raster/geometry/extrusion.h"

namespace tessera::geometry {
namespace {

// The body's width from tail (s = 0) to neck (s = 1), relative to SnakeShape::width, at evenly
// spaced knots: a fine tail tip, the thickest part two thirds along, a narrower neck where
// the wider head sits.
constexpr std::array<float, 9> kProfile = {0.05f, 0.32f, 0.56f, 0.76f, 0.9f, 0.98f, 1.0f, 0.86f, 0.7f};

float profile_at(float s) {
    const float x = std::clamp(s, 0.0f, 1.0f) * float(kProfile.size() - 1);
    const size_t i = std::min(size_t(x), kProfile.size() - 2);
    const float t = x - float(i);
    return kProfile[i] + (kProfile[i + 1] - kProfile[i]) * t;
}

glm::vec2 path_point(const SnakeShape& s, float angle) {
    const glm::vec2 local(s.path_radii.x * std::cos(angle), s.path_radii.y * std::sin(angle));
    const float c = std::cos(s.path_angle), n = std::sin(s.path_angle);
    return s.centre + glm::vec2(c * local.x - n * local.y, n * local.x + c * local.y);
}

}  // namespace

std::vector<glm::vec3> snake_spine(const SnakeShape& s, float time, const GroundHeight& ground) {
    const int k = s.control_points;
    const float direction = s.speed < 0.0f ? -1.0f : 1.0f;
    const float head_angle = s.phase + s.speed * time;
    // Arc length per radian of the path, its mean radius (the ellipse's circumference / 2 pi
    // to within a few per cent for the modest eccentricities used here).
    const float mean_radius = 0.5f * (s.path_radii.x + s.path_radii.y);
    std::vector<glm::vec3> points(static_cast<size_t>(k));
    for (int i = 0; i < k; ++i) {
        const int from_head = k - 1 - i;
        const float along = float(from_head) / float(k - 1) * s.length;
        const float angle = head_angle - direction * along / mean_radius;
        const glm::vec2 p = path_point(s, angle);
        const glm::vec2 ahead = path_point(s, angle + direction * 1e-3f);
        const glm::vec2 forward = glm::normalize(ahead - p);
        const glm::vec2 side(-forward.y, forward.x);
        // Each control point on its own closed curve: the path point plus a sideways sine of
        // its own period; the phase lags from head to tail so a wave runs down the body.
        const float period = s.wiggle_period * (1.0f + s.period_spread * float(from_head));
        const float sway_phase = glm::two_pi<float>() * time / period - s.wave_phase * float(from_head);
        const float envelope = 0.35f + 0.65f * std::min(1.0f, float(from_head) / 2.0f);
        const glm::vec2 xz = p + side * (s.wiggle * envelope * std::sin(sway_phase));
        const float s_body = float(i) / float(k - 1);
        const float half_height = s.width * s.height_ratio * profile_at(s_body);
        // Rest on the sand (sunk a little into it, as a heavy body would), the head raised.
        const float lift = from_head == 0 ? 0.45f * s.width : 0.0f;
        const float y = (ground ? ground(xz.x, xz.y) : 0.0f) + 0.8f * half_height + lift;
        points[size_t(i)] = glm::vec3(xz.x, y, xz.y);
    }
    return points;
}

Mesh snake_body(const SnakeShape& s, const std::vector<glm::vec3>& spine) {
    const BezierCurve<glm::vec3> curve = catmull_rom<glm::vec3>(spine);
    std::vector<glm::vec2> radii;
    for (size_t i = 0; i < kProfile.size(); ++i)
        // (a, b): along the frame's N (up, as the spine lies on the ground) and B (sideways).
        radii.emplace_back(s.width * s.height_ratio * kProfile[i], s.width * kProfile[i]);
    const BezierCurve<glm::vec2> profile = catmull_rom<glm::vec2>(radii);
    return extrude(curve, profile, s.tessellation.x, s.tessellation.y);
}

SnakeHead snake_head(const SnakeShape& s, const std::vector<glm::vec3>& spine) {
    const glm::vec3 neck = spine.back();
    glm::vec3 forward = neck - spine[spine.size() - 2];
    if (glm::length(forward) == 0.0f) forward = glm::vec3(1.0f, 0.0f, 0.0f);
    forward = glm::normalize(forward);
    const float yaw = std::atan2(-forward.z, forward.x);
    const float pitch = std::asin(std::clamp(forward.y, -1.0f, 1.0f));
    SnakeHead head;
    head.orientation = glm::angleAxis(yaw, glm::vec3(0.0f, 1.0f, 0.0f)) *
                       glm::angleAxis(pitch, glm::vec3(0.0f, 0.0f, 1.0f));
    head.radii = glm::vec3(2.1f, 0.62f, 0.95f) * s.width;
    // The neck ring of the body (open, semi-axes 0.7 width x 0.49 width) must lie inside the
    // head, or the floor shows through the gap: 0.4 of the head's length behind its centre its
    // cross-section is 0.92 of the widest (0.87 x 0.57 width).
    head.centre = neck + forward * (0.4f * head.radii.x);
    return head;
}

glm::vec3 snake_eye_offset(const SnakeHead& head, float side) {
    return glm::vec3(0.45f * head.radii.x, 0.45f * head.radii.y, side * 0.72f * head.radii.z);
}

float snake_eye_radius(const SnakeShape& s) { return 0.24f * s.width; }

}  // namespace tessera::geometry
