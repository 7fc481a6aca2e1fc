#include "raster/embree/pixel_rays.h"

#include <stdexcept>

namespace tessera::rt {

PixelRays::PixelRays(const glm::mat4& view_projection, int width, int height)
    : view_projection_(view_projection),
      inverse_(glm::inverse(glm::dmat4(view_projection))),
      width_(width),
      height_(height) {
    if (width <= 0 || height <= 0)
        throw std::invalid_argument("image size " + std::to_string(width) + "x" +
                                    std::to_string(height) + " is not positive");
}

void PixelRays::ray(float x_centre, float y_centre, glm::vec3& origin,
                    glm::vec3& direction) const {
    // Window to NDC, rows top to bottom (camera.h): y_ndc = 1 - 2 y / height.
    const double x_ndc = 2.0 * double(x_centre) / width_ - 1.0;
    const double y_ndc = 1.0 - 2.0 * double(y_centre) / height_;
    const glm::dvec4 on_near = inverse_ * glm::dvec4(x_ndc, y_ndc, -1.0, 1.0);
    const glm::dvec4 on_far = inverse_ * glm::dvec4(x_ndc, y_ndc, 1.0, 1.0);
    const glm::dvec3 near_point = glm::dvec3(on_near) / on_near.w;
    const glm::dvec3 far_point = glm::dvec3(on_far) / on_far.w;
    origin = glm::vec3(near_point);
    direction = glm::vec3(far_point - near_point);
}

float PixelRays::window_depth(const glm::vec3& world) const {
    const glm::dvec4 clip = view_projection_ * glm::dvec4(glm::dvec3(world), 1.0);
    return float(clip.z / clip.w * 0.5 + 0.5);
}

}  // namespace tessera::rt
