#include "raster/scene/transform.h"

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <stdexcept>

#include "raster/core/direction.h"

namespace tessera::scene {
namespace {

void check(const Transform& t) {
    for (int i = 0; i < 3; ++i)
        if (!std::isfinite(t.scale[i]) || t.scale[i] == 0.0f)
            throw std::invalid_argument("transform: scale components must be finite and non-zero");
    if (!std::isfinite(t.angle))
        throw std::invalid_argument("transform: rotation angle must be finite");
    if (t.angle != 0.0f && !normalisable(t.axis))
        throw std::invalid_argument("transform: rotation axis must be finite and not zero");
}

glm::mat4 rotation(float angle, glm::vec3 axis) {
    if (angle == 0.0f) return glm::mat4(1.0f);
    return glm::rotate(glm::mat4(1.0f), angle, *unit_direction(axis));  // any length (direction.h)
}

}  // namespace

glm::mat4 Transform::model() const {
    check(*this);
    return glm::translate(glm::mat4(1.0f), translation) * rotation(angle, axis) *
           glm::scale(glm::mat4(1.0f), scale);
}

glm::mat4 Transform::inverse() const {
    check(*this);
    return glm::scale(glm::mat4(1.0f), 1.0f / scale) * rotation(-angle, axis) *
           glm::translate(glm::mat4(1.0f), -translation);
}

glm::mat3 Transform::normal_matrix() const { return glm::transpose(glm::mat3(inverse())); }

}  // namespace tessera::scene
