// The writhing snakes (a classic graphics-course exercise), as geometry over time: the spine's
// control points (SnakeShape: riding a closed path, each swaying on its own period), the body
// as the elliptical-profile extrusion along the Catmull-Rom/Bezier spine through them
// (geometry/extrusion.h), and the pose of the ellipsoid head and eyes at the spine's front.
// Every function is a pure function of the spec and the time, so objects animated in parallel
// (Scene::animate) agree on where the snake is without sharing state.
#pragma once
#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include <functional>
#include <vector>

#include "raster/core/mesh.h"

namespace tessera::geometry {

// The ground under the snakes: world height at (x, z).
// A snake. Its spine's control points ride a closed path (an
// ellipse around `centre`, turned by `path_angle`) at `speed` rad/s, spaced along it so the
// body spans `length`, and each sways sideways on its own closed curve: a sine of period
// wiggle_period * (1 + period_spread * i) and phase -wave_phase * i (a wave running from head
// to tail whose control points drift in and out of step: the writhing).
struct SnakeShape {
    glm::vec2 centre{0.0f};
    glm::vec2 path_radii{2.0f, 1.5f};
    float path_angle = 0.0f;  // radians about +y
    float phase = 0.0f;       // the head's start angle on the path
    float speed = 0.25f;      // rad/s; negative: clockwise
    float length = 3.0f;
    float width = 0.12f;         // the body's largest horizontal semi-axis
    float height_ratio = 0.7f;   // vertical / horizontal semi-axis
    int control_points = 10;
    float wiggle = 0.22f;        // sideways sway amplitude
    float wiggle_period = 1.7f;  // seconds
    float period_spread = 0.11f;
    float wave_phase = 0.9f;     // radians per control point
    glm::ivec2 tessellation{192, 20};  // along the body, around it
};

using GroundHeight = std::function<float(float x, float z)>;

// Control points from tail (index 0) to head, world space, resting on the ground.
std::vector<glm::vec3> snake_spine(const SnakeShape& snake, float time, const GroundHeight& ground);

// The body: the extrusion along the spine with the snake's tapering elliptical profile
// (uv = (along from the tail, around)).
Mesh snake_body(const SnakeShape& snake, const std::vector<glm::vec3>& spine);

// Where the head sits and which way it looks (unit quaternion taking the model's +x to the
// spine's forward direction, its +y to the ground's up as far as the spine's slope allows).
struct SnakeHead {
    glm::vec3 centre;
    glm::quat orientation;
    glm::vec3 radii;  // ellipsoid semi-axes in the head's frame (forward, up, side)
};
SnakeHead snake_head(const SnakeShape& snake, const std::vector<glm::vec3>& spine);

// The eyes' centres in the head's frame (side = -1 left, +1 right) and their radius.
glm::vec3 snake_eye_offset(const SnakeHead& head, float side);
float snake_eye_radius(const SnakeShape& snake);

}  // namespace tessera::geometry
