#include "raster/scene/scene.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "raster/core/direction.h"

#include <cmath>
#include <cstring>
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

void validate_materials(const Scene& scene) {
    for (size_t i = 0; i < scene.materials.size(); ++i)
        if (!texture_ok(scene.materials[i].diffuse_texture, scene.textures.size()) ||
            !texture_ok(scene.materials[i].normal_texture, scene.textures.size()))
            throw std::invalid_argument("material " + std::to_string(i) + " refers to a texture that does not exist");
}

// Everything validate() checks of an object but its indices.
void validate_object_shape(const Object& o, size_t materials) {
    const std::string who = "object '" + o.name + "'";
    if (!o.geometry) throw std::invalid_argument(who + " has no geometry");
    if (o.material >= materials)
        throw std::invalid_argument(who + " refers to material " + std::to_string(o.material) +
                                    ", but the scene has " + std::to_string(materials));
    const Mesh& m = *o.geometry;
    if (m.indices.size() % 3 != 0 || (!m.normals.empty() && m.normals.size() != m.positions.size()) ||
        (!m.uvs.empty() && m.uvs.size() != m.positions.size()) ||
        (!m.tangents.empty() && m.tangents.size() != m.positions.size()))
        throw std::invalid_argument(who + " has inconsistent mesh attribute sizes");
}

void validate_object_indices(const Object& o) {
    const Mesh& m = *o.geometry;
    for (uint32_t index : m.indices)
        if (index >= m.positions.size())
            throw std::invalid_argument("object '" + o.name + "' has a vertex index out of range");
}

}  // namespace

void Scene::animate(float time) {
    tbb::parallel_for(size_t(0), objects.size(), [&](size_t i) {
        if (objects[i].animate) objects[i].animate(objects[i], time);
    });
}

void Scene::validate() const {
    validate_materials(*this);
    for (const Object& o : objects) {
        validate_object_shape(o, materials.size());
        validate_object_indices(o);
    }
}

namespace {

BakeLayout layout_of(const Scene& scene) {
    const size_t n = scene.objects.size();
    BakeLayout l;
    l.first_vertex.assign(n + 1, 0);
    l.first_index.assign(n + 1, 0);
    l.tangents = n > 0;
    for (size_t i = 0; i < n; ++i) {
        const Mesh& m = *scene.objects[i].geometry;
        l.first_vertex[i + 1] = l.first_vertex[i] + m.vertex_count();
        l.first_index[i + 1] = l.first_index[i] + m.indices.size();
        l.normals |= !m.normals.empty();
        l.uvs |= !m.uvs.empty();
        l.tangents &= !m.tangents.empty();
    }
    if (l.first_vertex[n] > std::numeric_limits<uint32_t>::max())
        throw std::invalid_argument("the scene has more vertices than 32-bit indices can address");
    return l;
}

// Sizes the bake's arrays for `l` (their contents are left to bake_object) and lists the parts.
void allocate(const Scene& scene, const BakeLayout& l, BakedScene& baked) {
    const size_t n = scene.objects.size(), vertices = l.first_vertex[n], indices = l.first_index[n];
    Mesh& out = baked.mesh;
    out.positions.resize(vertices);
    out.normals.resize(l.normals ? vertices : 0);
    out.uvs.resize(l.uvs ? vertices : 0);
    out.tangents.resize(l.tangents ? vertices : 0);
    out.indices.resize(indices);
    baked.triangle_material.resize(indices / 3);
    baked.vertex_material.resize(vertices);
}

void list_parts(const Scene& scene, const BakeLayout& l, BakedScene& baked) {
    const size_t n = scene.objects.size();
    baked.objects.resize(n);
    for (size_t i = 0; i < n; ++i)
        baked.objects[i] = MeshPart{l.first_vertex[i], l.first_vertex[i + 1] - l.first_vertex[i], l.first_index[i] / 3,
                                    (l.first_index[i + 1] - l.first_index[i]) / 3, !scene.objects[i].animate};
}

// Object i's vertices and triangles into their place: every value of its range is written
// (zeros for attributes the object lacks), so the result does not depend on what was there.
void bake_object(const Scene& scene, size_t i, const BakeLayout& l, BakedScene& baked) {
    Mesh& out = baked.mesh;
    const Object& o = scene.objects[i];
    const Mesh& m = *o.geometry;
    const glm::mat4 model = o.transform.model();
    const glm::mat3 normal_matrix = o.transform.normal_matrix();
    const glm::mat3 linear(model);
    const bool mirrored = glm::determinant(linear) < 0.0f;
    const size_t v0 = l.first_vertex[i];
    tbb::parallel_for(tbb::blocked_range<size_t>(0, m.vertex_count(), 4096), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t k = r.begin(); k < r.end(); ++k) {
            out.positions[v0 + k] = glm::vec3(model * glm::vec4(m.positions[k], 1.0f));
            if (l.normals)
                out.normals[v0 + k] = m.normals.empty() ? glm::vec3(0.0f) : unit_or_zero(normal_matrix * m.normals[k]);
            if (l.uvs) out.uvs[v0 + k] = m.uvs.empty() ? glm::vec2(0.0f) : m.uvs[k];
            if (l.tangents) {
                const glm::vec3 tw = linear * glm::vec3(m.tangents[k]);
                out.tangents[v0 + k] = glm::vec4(unit_or_zero(tw), mirrored ? -m.tangents[k].w : m.tangents[k].w);
            }
            baked.vertex_material[v0 + k] = o.material;
        }
    });
    const size_t i0 = l.first_index[i];
    tbb::parallel_for(tbb::blocked_range<size_t>(0, m.triangle_count(), 4096), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t t = r.begin(); t < r.end(); ++t) {
            const uint32_t a = m.indices[3 * t], b = m.indices[3 * t + 1], c = m.indices[3 * t + 2];
            uint32_t* dst = &out.indices[i0 + 3 * t];
            dst[0] = uint32_t(v0) + a;
            dst[1] = uint32_t(v0) + (mirrored ? c : b);
            dst[2] = uint32_t(v0) + (mirrored ? b : c);
            baked.triangle_material[i0 / 3 + t] = o.material;
        }
    });
}

}  // namespace

BakedScene bake(const Scene& scene) {
    scene.validate();
    const BakeLayout l = layout_of(scene);
    BakedScene baked;
    allocate(scene, l, baked);
    list_parts(scene, l, baked);
    tbb::parallel_for(size_t(0), scene.objects.size(), [&](size_t i) { bake_object(scene, i, l, baked); });
    return baked;
}

const BakedScene& SceneBaker::bake(const Scene& scene) {
    validate_materials(scene);
    for (const Object& o : scene.objects) validate_object_shape(o, scene.materials.size());
    const size_t n = scene.objects.size();
    const auto same_object = [&](size_t i) {
        const Object& o = scene.objects[i];
        return i < baked_objects_.size() && baked_objects_[i].geometry == o.geometry &&
               baked_objects_[i].material == o.material &&
               std::memcmp(&baked_objects_[i].transform, &o.transform, sizeof(Transform)) == 0;
    };
    // An object's indices are checked when its geometry is new to this slot (a mesh is
    // immutable once shared, and the one baked last is held, so its address is not reused).
    for (size_t i = 0; i < n; ++i)
        if (i >= baked_objects_.size() || baked_objects_[i].geometry != scene.objects[i].geometry)
            validate_object_indices(scene.objects[i]);
    BakeLayout l = layout_of(scene);
    const bool same_layout = layout_ && *layout_ == l;
    std::vector<size_t> changed;
    for (size_t i = 0; i < n; ++i)
        if (!same_layout || !same_object(i)) changed.push_back(i);
    // Until the bake below has succeeded, nothing of the previous one is trusted.
    baked_objects_.clear();
    layout_.reset();
    allocate(scene, l, baked_);
    list_parts(scene, l, baked_);
    tbb::parallel_for(size_t(0), changed.size(), [&](size_t k) { bake_object(scene, changed[k], l, baked_); });
    objects_baked_ = changed.size();
    baked_objects_.resize(n);
    for (size_t i = 0; i < n; ++i)
        baked_objects_[i] = {scene.objects[i].geometry, scene.objects[i].transform, scene.objects[i].material};
    layout_ = std::move(l);
    return baked_;
}

}  // namespace tessera::scene
