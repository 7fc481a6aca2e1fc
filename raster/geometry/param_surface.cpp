#include "raster/geometry/param_surface.h"

#include <tbb/parallel_for.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace tessera::geometry {
namespace {

glm::vec3 unit_or(glm::vec3 v, glm::vec3 fallback) {
    const float len = glm::length(v);
    return len > 0.0f && std::isfinite(len) ? v / len : fallback;
}

// Any unit vector perpendicular to n: the tangent where dr/du vanishes.
glm::vec3 perpendicular(glm::vec3 n) {
    const glm::vec3 other = std::abs(n.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
    return glm::normalize(glm::cross(other, n));
}

}  // namespace

Mesh tessellate(const SurfaceFunction& surface, int n, int m) {
    if (n < 1 || m < 1)
        throw std::invalid_argument("tessellation needs N, M >= 1, got " + std::to_string(n) +
                                    " x " + std::to_string(m));
    const uint64_t vertices = uint64_t(n + 1) * uint64_t(m + 1);
    if (vertices > std::numeric_limits<uint32_t>::max() / 2)
        throw std::invalid_argument("tessellation of " + std::to_string(n) + " x " +
                                    std::to_string(m) + " is too fine for 32-bit indices");
    const size_t stride = size_t(m) + 1;
    Mesh mesh;
    mesh.positions.resize(vertices);
    mesh.normals.resize(vertices);
    mesh.uvs.resize(vertices);
    mesh.tangents.resize(vertices);
    mesh.indices.resize(size_t(n) * size_t(m) * 6);

    tbb::parallel_for(0, n + 1, [&](int i) {
        const float u = float(i) / float(n);
        for (int j = 0; j <= m; ++j) {
            const float v = float(j) / float(m);
            const SurfacePoint p = surface(u, v);
            const size_t k = size_t(i) * stride + size_t(j);
            const glm::vec3 normal = unit_or(p.normal, glm::vec3(0, 0, 1));
            mesh.positions[k] = p.position;
            mesh.normals[k] = normal;
            mesh.uvs[k] = {u, v};
            mesh.tangents[k] = glm::vec4(unit_or(p.dpdu, perpendicular(normal)), 1.0f);
        }
    });

    // Winding: each quad's two triangles are made counter-clockwise as seen from the side the
    // analytic normals point to. The order (i,j) (i+1,j) (i,j+1) is counter-clockwise
    // when n ~ dr/du x dr/dv (the flag) but not for its sphere, whose closed-form normal is
    // -dr/du x dr/dv; deciding per quad from the diagonals' cross product (non-zero even
    // where an edge collapses at a pole) covers every surface.
    tbb::parallel_for(0, n, [&](int i) {
        const auto at = [&](int a, int b) { return uint32_t(size_t(a) * stride + size_t(b)); };
        uint32_t* out = mesh.indices.data() + size_t(i) * size_t(m) * 6;
        for (int j = 0; j < m; ++j) {
            const uint32_t a = at(i, j), b = at(i + 1, j), c = at(i, j + 1), d = at(i + 1, j + 1);
            const glm::vec3 diagonals = glm::cross(mesh.positions[d] - mesh.positions[a],
                                                   mesh.positions[c] - mesh.positions[b]);
            const glm::vec3 normals = mesh.normals[a] + mesh.normals[b] + mesh.normals[c] +
                                      mesh.normals[d];
            const bool keep = glm::dot(diagonals, normals) >= 0.0f;
            const uint32_t quad[6] = {a, keep ? b : c, keep ? c : b, b, keep ? d : c, keep ? c : d};
            for (uint32_t q : quad) *out++ = q;
        }
    });
    return mesh;
}

}  // namespace tessera::geometry
