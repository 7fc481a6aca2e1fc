// The writhing snakes of the seeds/000 homework, as geometry over time: the spine's control
// points (SnakeSpec: riding a closed path, each swaying on its own period), the body as the
// elliptical-profile extrusion along the Catmull-Rom/Bezier spine through them
// (geometry/extrusion.h), and the pose of the ellipsoid head and eyes at the spine's front.
// Every function is a pure function of the spec and the time, so objects animated in
// parallel (Scene::animate) agree on where the snake is without sharing state.
#pragma once
#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include <functional>
#include <vector>

#include "raster/mesh.h"
#include "raster/scene_file/scene_spec.h"

namespace tessera {

// The ground under the snakes: world height at (x, z).
using GroundHeight = std::function<float(float x, float z)>;

// Control points from tail (index 0) to head, world space, resting on the ground.
std::vector<glm::vec3> snake_spine(const SnakeSpec& snake, float time, const GroundHeight& ground);

// The body: the extrusion along the spine with the snake's tapering elliptical profile
// (uv = (along from the tail, around)).
Mesh snake_body(const SnakeSpec& snake, const std::vector<glm::vec3>& spine);

// Where the head sits and which way it looks (unit quaternion taking the model's +x to the
// spine's forward direction, its +y to the ground's up as far as the spine's slope allows).
struct SnakeHead {
    glm::vec3 centre;
    glm::quat orientation;
    glm::vec3 radii;  // ellipsoid semi-axes in the head's frame (forward, up, side)
};
SnakeHead snake_head(const SnakeSpec& snake, const std::vector<glm::vec3>& spine);

// The eyes' centres in the head's frame (side = -1 left, +1 right) and their radius.
glm::vec3 snake_eye_offset(const SnakeHead& head, float side);
float snake_eye_radius(const SnakeSpec& snake);

}  // namespace tessera
