#include "raster/scene/transform.h"

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <stdexcept>

namespace tessera::scene {
namespace {

void check(const Transform& t) {
    for (int i = 0; i < 3; ++i)
        if (!std::isfinite(t.scale[i]) || t.scale[i] == 0.0f)
            throw std::invalid_argument("transform: scale components must be finite and non-zero");
    if (!std::isfinite(t.angle))
        throw std::invalid_argument("transform: rotation angle must be finite");
    if (t.angle != 0.0f && !(glm::length(t.axis) > 0.0f))
        throw std::invalid_argument("transform: rotation axis must not be zero");
}

glm::mat4 rotation(float angle, glm::vec3 axis) {
    if (angle == 0.0f) return glm::mat4(1.0f);
    return glm::rotate(glm::mat4(1.0f), angle, glm::normalize(axis));
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
