#include "raster/scene/scene.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "raster/core/direction.h"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace tessera::scene {
namespace {

bool texture_ok(int32_t index, size_t count) {
    return index == kNoTexture || (index >= 0 && size_t(index) < count);
}

// A transformed normal or tangent at unit length, zero when it has none. A scale of 1e-30 or
// 1e30 makes its square overflow or underflow: such a vector is scaled first
// (core/direction.h); every other is divided by its length as always (the same bits).
glm::vec3 unit_or_zero(glm::vec3 v) {
    const float len = glm::length(v);
    if (std::isfinite(len) && len >= 1.1e-19f) return v / len;  // 1.1e-19: sqrt(FLT_MIN)
    const auto scaled = normalisable(v);
    return scaled ? *scaled / glm::length(*scaled) : glm::vec3(0.0f);
}

}  // namespace

void Scene::animate(float time) {
    tbb::parallel_for(size_t(0), objects.size(), [&](size_t i) {
        if (objects[i].animate) objects[i].animate(objects[i], time);
    });
}

void Scene::validate() const {
    for (size_t i = 0; i < materials.size(); ++i)
        if (!texture_ok(materials[i].diffuse_texture, textures.size()) ||
            !texture_ok(materials[i].normal_texture, textures.size()))
            throw std::invalid_argument("material " + std::to_string(i) +
                                        " refers to a texture that does not exist");
    for (const Object& o : objects) {
        const std::string who = "object '" + o.name + "'";
        if (!o.geometry) throw std::invalid_argument(who + " has no geometry");
        if (o.material >= materials.size())
            throw std::invalid_argument(who + " refers to material " + std::to_string(o.material) +
                                        ", but the scene has " + std::to_string(materials.size()));
        const Mesh& m = *o.geometry;
        if (m.indices.size() % 3 != 0 || (!m.normals.empty() && m.normals.size() != m.positions.size()) ||
            (!m.uvs.empty() && m.uvs.size() != m.positions.size()) ||
            (!m.tangents.empty() && m.tangents.size() != m.positions.size()))
            throw std::invalid_argument(who + " has inconsistent mesh attribute sizes");
        for (uint32_t index : m.indices)
            if (index >= m.positions.size())
                throw std::invalid_argument(who + " has a vertex index out of range");
    }
}

BakedScene bake(const Scene& scene) {
    scene.validate();
    const size_t n = scene.objects.size();
    std::vector<size_t> first_vertex(n + 1, 0), first_index(n + 1, 0);
    bool normals = false, uvs = false, tangents = n > 0;
    for (size_t i = 0; i < n; ++i) {
        const Mesh& m = *scene.objects[i].geometry;
        first_vertex[i + 1] = first_vertex[i] + m.vertex_count();
        first_index[i + 1] = first_index[i] + m.indices.size();
        normals |= !m.normals.empty();
        uvs |= !m.uvs.empty();
        tangents &= !m.tangents.empty();
    }
    if (first_vertex[n] > std::numeric_limits<uint32_t>::max())
        throw std::invalid_argument("the scene has more vertices than 32-bit indices can address");

    BakedScene baked;
    Mesh& out = baked.mesh;
    out.positions.resize(first_vertex[n]);
    if (normals) out.normals.assign(first_vertex[n], glm::vec3(0.0f));
    if (uvs) out.uvs.assign(first_vertex[n], glm::vec2(0.0f));
    if (tangents) out.tangents.resize(first_vertex[n]);
    out.indices.resize(first_index[n]);
    baked.triangle_material.resize(first_index[n] / 3);
    baked.vertex_material.resize(first_vertex[n]);
    baked.objects.resize(n);
    for (size_t i = 0; i < n; ++i)
        baked.objects[i] = MeshPart{first_vertex[i], first_vertex[i + 1] - first_vertex[i], first_index[i] / 3,
                                    (first_index[i + 1] - first_index[i]) / 3, !scene.objects[i].animate};

    tbb::parallel_for(size_t(0), n, [&](size_t i) {
        const Object& o = scene.objects[i];
        const Mesh& m = *o.geometry;
        const glm::mat4 model = o.transform.model();
        const glm::mat3 normal_matrix = o.transform.normal_matrix();
        const glm::mat3 linear(model);
        const bool mirrored = glm::determinant(linear) < 0.0f;
        const size_t v0 = first_vertex[i];
        tbb::parallel_for(tbb::blocked_range<size_t>(0, m.vertex_count(), 4096),
                          [&](const tbb::blocked_range<size_t>& r) {
            for (size_t k = r.begin(); k < r.end(); ++k) {
                out.positions[v0 + k] = glm::vec3(model * glm::vec4(m.positions[k], 1.0f));
                if (!m.normals.empty()) out.normals[v0 + k] = unit_or_zero(normal_matrix * m.normals[k]);
                if (!m.uvs.empty()) out.uvs[v0 + k] = m.uvs[k];
                if (tangents) {
                    const glm::vec3 tw = linear * glm::vec3(m.tangents[k]);
                    out.tangents[v0 + k] = glm::vec4(unit_or_zero(tw),
                                                     mirrored ? -m.tangents[k].w : m.tangents[k].w);
                }
                baked.vertex_material[v0 + k] = o.material;
            }
        });
        const size_t i0 = first_index[i];
        tbb::parallel_for(tbb::blocked_range<size_t>(0, m.triangle_count(), 4096),
                          [&](const tbb::blocked_range<size_t>& r) {
            for (size_t t = r.begin(); t < r.end(); ++t) {
                const uint32_t a = m.indices[3 * t], b = m.indices[3 * t + 1], c = m.indices[3 * t + 2];
                uint32_t* dst = &out.indices[i0 + 3 * t];
                dst[0] = uint32_t(v0) + a;
                dst[1] = uint32_t(v0) + (mirrored ? c : b);
                dst[2] = uint32_t(v0) + (mirrored ? b : c);
                baked.triangle_material[i0 / 3 + t] = o.material;
            }
        });
    });
    return baked;
}

}  // namespace tessera::scene
