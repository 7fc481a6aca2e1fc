#include "raster/embree/pixel_rays.h"

#include <stdexcept>
#include <string>

namespace tessera::rt {

PixelRays::PixelRays(const glm::mat4& view_projection, int width, int height)
    : view_projection_(view_projection), width_(width), height_(height) {
    if (width <= 0 || height <= 0)
        throw std::invalid_argument("image size " + std::to_string(width) + "x" +
                                    std::to_string(height) + " is not positive");
    // inverse * (x_ndc, y_ndc, z, 1) with x_ndc = 2x/W - 1, y_ndc = 1 - 2y/H (rows top to
    // bottom, camera.h) is affine in the window position (x, y): fold the mapping in, once,
    // in double.
    const glm::dmat4 inverse = glm::inverse(glm::dmat4(view_projection));
    const glm::dvec4 per_x = inverse[0] * (2.0 / width), per_y = inverse[1] * (-2.0 / height);
    const glm::dvec4 at_zero = inverse[3] - inverse[0] + inverse[1];
    near_ = {glm::vec4(at_zero - inverse[2]), glm::vec4(per_x), glm::vec4(per_y)};
    far_ = {glm::vec4(at_zero + inverse[2]), glm::vec4(per_x), glm::vec4(per_y)};
}

void PixelRays::ray(float x_centre, float y_centre, glm::vec3& origin,
                    glm::vec3& direction) const {
    const glm::vec4 on_near = near_.at(x_centre, y_centre);
    const glm::vec4 on_far = far_.at(x_centre, y_centre);
    origin = glm::vec3(on_near) / on_near.w;
    direction = glm::vec3(on_far) / on_far.w - origin;
}

float PixelRays::window_depth(const glm::vec3& world) const {
    const glm::dvec4 clip = view_projection_ * glm::dvec4(glm::dvec3(world), 1.0);
    return float(clip.z / clip.w * 0.5 + 0.5);
}

}  // namespace tessera::rt
