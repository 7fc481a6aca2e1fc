#include "raster/scene/instance_grid.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace tessera::scene {

InstanceGrid::InstanceGrid(int n, glm::vec3 lower, glm::vec3 upper) : copies(n) {
    if (n < 1) throw std::invalid_argument("a grid needs at least one copy, got " + std::to_string(n));
    for (int k = 0; k < 3; ++k)
        if (!std::isfinite(lower[k]) || !std::isfinite(upper[k]) || lower[k] > upper[k])
            throw std::invalid_argument("a grid needs a finite bounding box");
    columns = int(std::ceil(std::sqrt(double(n))));
    rows = (n + columns - 1) / columns;
    const glm::vec3 size = upper - lower;
    const float gap = 0.25f * std::max({size.x, size.y, size.z, 1e-6f});
    cell = glm::vec2(size.x + gap, size.z + gap);
}

glm::vec3 InstanceGrid::offset(int copy) const {
    return {float(copy % columns) * cell.x, 0.0f, float(copy / columns) * cell.y};
}

std::pair<glm::vec3, glm::vec3> InstanceGrid::bounds(glm::vec3 lower, glm::vec3 upper) const {
    // The last column is full only when some row reaches it: the first row always does.
    const glm::vec3 far_corner = offset(std::min(copies, columns) - 1) + glm::vec3(0.0f, 0.0f, float(rows - 1) * cell.y);
    return {lower, upper + far_corner};
}

Scene instance_grid(const Scene& scene, const InstanceGrid& grid) {
    Scene out;
    out.camera = scene.camera;
    out.materials = scene.materials;
    out.textures = scene.textures;
    out.lights = scene.lights;
    out.background = scene.background;
    out.objects.reserve(scene.objects.size() * size_t(grid.copies));
    for (int c = 0; c < grid.copies; ++c)
        for (const Object& o : scene.objects) {
            Object copy;
            copy.name = o.name;
            copy.geometry = o.geometry;
            copy.material = o.material;
            copy.transform = o.transform;
            // Translation comes last in the model matrix (transform.h), so this moves the
            // object in world space without changing its shape.
            copy.transform.translation += grid.offset(c);
            out.objects.push_back(std::move(copy));
        }
    return out;
}

}  // namespace tessera::scene
