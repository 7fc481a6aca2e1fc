#include "raster/asset/light_rig.h"

#include <algorithm>

namespace tessera::asset {

std::vector<scene::Light> default_light_rig(const Camera& camera, glm::vec3 lower, glm::vec3 upper) {
    const glm::vec3 centre = 0.5f * (lower + upper);
    const float radius = std::max(0.5f * glm::length(upper - lower), 1e-6f);
    // The camera's frame: back towards the eye, right, up.
    glm::vec3 back = camera.eye - camera.lookat;
    back = glm::length(back) > 0.0f ? glm::normalize(back) : glm::vec3(0.0f, 0.0f, 1.0f);
    glm::vec3 right = glm::cross(camera.up, back);
    right = glm::length(right) > 0.0f ? glm::normalize(right) : glm::vec3(1.0f, 0.0f, 0.0f);
    const glm::vec3 up = glm::cross(back, right);
    const auto place = [&](float r, float u, float b) {
        return centre + glm::normalize(right * r + up * u + back * b) * (4.0f * radius);
    };
    return {scene::point_light(place(-0.6f, 0.8f, 0.7f), glm::vec3(0.12f), glm::vec3(0.8f)),
            scene::point_light(place(0.8f, -0.2f, 0.6f), glm::vec3(0.0f), glm::vec3(0.3f))};
}

}  // namespace tessera::asset
