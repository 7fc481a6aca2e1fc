// An object's placement: scale, then rotation by `angle` about `axis`, then
// translation. Written for row vectors, M = S * R(angle, axis) * T, and its inverse
// Minv = T(-pos) * R(-angle, axis) * S(1/scale); with GLM's column vectors the same transforms
// are T * R * S and S^-1 * R^-1 * T^-1. Normals go through the inverse transpose
// (`Minv * n`, a row vector times the transpose), so non-uniform scales keep them perpendicular.
#pragma once
#include <glm/glm.hpp>

namespace tessera::scene {

struct Transform {
    glm::vec3 scale{1.0f};
    glm::vec3 axis{0.0f, 1.0f, 0.0f};  // rotation axis; need not be unit length
    float angle = 0.0f;                // radians, right-handed about `axis`
    glm::vec3 translation{0.0f};

    // Throws std::invalid_argument for a zero or non-finite scale component, or a zero axis
    // with a non-zero angle: such a transform has no inverse for the normals.
    glm::mat4 model() const;
    glm::mat4 inverse() const;
    // The upper 3x3 of inverse() transposed: n_world = normal_matrix() * n_model.
    glm::mat3 normal_matrix() const;
};

}  // namespace tessera::scene
