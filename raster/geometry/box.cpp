#include "raster/geometry/box.h"

#include <stdexcept>

namespace tessera::geometry {

Mesh box_mesh(glm::vec3 half_extent) {
    if (!(half_extent.x > 0.0f && half_extent.y > 0.0f && half_extent.z > 0.0f))
        throw std::invalid_argument("box half extents must be positive");
    Mesh m;
    // Each face: outward normal n, and the directions s (uv u) and t (uv v) with s x t = n.
    const glm::vec3 faces[6][3] = {
        {{1, 0, 0}, {0, 0, -1}, {0, 1, 0}},  {{-1, 0, 0}, {0, 0, 1}, {0, 1, 0}},
        {{0, 1, 0}, {1, 0, 0}, {0, 0, -1}},  {{0, -1, 0}, {1, 0, 0}, {0, 0, 1}},
        {{0, 0, 1}, {1, 0, 0}, {0, 1, 0}},   {{0, 0, -1}, {-1, 0, 0}, {0, 1, 0}},
    };
    for (const auto& f : faces) {
        const glm::vec3 n = f[0], s = f[1], t = f[2];
        const uint32_t base = uint32_t(m.positions.size());
        for (int k = 0; k < 4; ++k) {
            const float u = float(k & 1), v = float(k >> 1);
            m.positions.push_back(half_extent * (n + (2.0f * u - 1.0f) * s + (2.0f * v - 1.0f) * t));
            m.normals.push_back(n);
            m.uvs.push_back({u, v});
            m.tangents.push_back(glm::vec4(s, 1.0f));
        }
        for (uint32_t i : {0u, 1u, 2u, 1u, 3u, 2u}) m.indices.push_back(base + i);
    }
    return m;
}

}  // namespace tessera::geometry
