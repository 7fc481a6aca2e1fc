#include "raster/workloads/test_meshes.h"

#include <cmath>
#include <numbers>

#include "procedural/hash.h"

namespace tessera::workloads {

using procedural::SplitMix64;

Mesh to_world(const WindowMesh& window, const glm::mat4& view_projection, int width, int height) {
    const glm::mat4 inverse = glm::inverse(view_projection);
    Mesh mesh;
    mesh.positions.reserve(window.positions.size());
    mesh.uvs.reserve(window.positions.size());
    for (const glm::vec3& p : window.positions) {
        const glm::vec4 ndc(2.0f * p.x / float(width) - 1.0f, 1.0f - 2.0f * p.y / float(height),
                            2.0f * p.z - 1.0f, 1.0f);
        const glm::vec4 world = inverse * ndc;
        mesh.positions.push_back(glm::vec3(world) / world.w);
        mesh.uvs.push_back({p.x / float(width), 1.0f - p.y / float(height)});
    }
    mesh.indices = window.indices;
    return mesh;
}

WindowMesh random_triangles(uint64_t seed, size_t count, int width, int height, float max_size,
                            float margin) {
    SplitMix64 rng(seed);
    WindowMesh m;
    m.positions.reserve(3 * count);
    m.indices.reserve(3 * count);
    for (size_t t = 0; t < count; ++t) {
        const float cx = -margin + rng.next_float() * (float(width) + 2 * margin);
        const float cy = -margin + rng.next_float() * (float(height) + 2 * margin);
        for (int k = 0; k < 3; ++k) {
            m.indices.push_back(uint32_t(m.positions.size()));
            m.positions.push_back({cx + (rng.next_float() - 0.5f) * max_size,
                                   cy + (rng.next_float() - 0.5f) * max_size, rng.next_float()});
        }
    }
    return m;
}

WindowMesh fill_rate(uint64_t seed, size_t count, float leg, int width, int height) {
    SplitMix64 rng(seed);
    WindowMesh m;
    m.positions.reserve(3 * count);
    m.indices.reserve(3 * count);
    for (size_t t = 0; t < count; ++t) {
        const float x = rng.next_float() * (float(width) - leg);
        const float y = rng.next_float() * (float(height) - leg);
        // Back to front: depth falls from 0.9 towards 0.1 in submission order.
        const float z = 0.9f - 0.8f * float(t) / float(count);
        const uint32_t base = uint32_t(m.positions.size());
        if (t % 2 == 0) {
            m.positions.insert(m.positions.end(), {{x, y, z}, {x + leg, y, z}, {x, y + leg, z}});
        } else {
            m.positions.insert(m.positions.end(), {{x + leg, y, z}, {x + leg, y + leg, z}, {x, y + leg, z}});
        }
        m.indices.insert(m.indices.end(), {base, base + 1, base + 2});
    }
    return m;
}

WindowMesh grid(uint64_t seed, int cells_x, int cells_y, float x0, float y0, float x1, float y1,
                float jitter) {
    SplitMix64 rng(seed);
    WindowMesh m;
    const float sx = (x1 - x0) / float(cells_x), sy = (y1 - y0) / float(cells_y);
    for (int j = 0; j <= cells_y; ++j)
        for (int i = 0; i <= cells_x; ++i) {
            float x = x0 + float(i) * sx, y = y0 + float(j) * sy;
            const bool interior = i > 0 && j > 0 && i < cells_x && j < cells_y;
            if (interior && jitter > 0) {
                x += (rng.next_float() - 0.5f) * 2.0f * jitter * sx;
                y += (rng.next_float() - 0.5f) * 2.0f * jitter * sy;
            }
            m.positions.push_back({x, y, 0.25f + 0.5f * rng.next_float()});
        }
    const uint32_t row = uint32_t(cells_x + 1);
    for (int j = 0; j < cells_y; ++j)
        for (int i = 0; i < cells_x; ++i) {
            const uint32_t a = uint32_t(j) * row + uint32_t(i), b = a + 1, c = a + row, d = c + 1;
            if ((i + j) % 2 == 0)
                m.indices.insert(m.indices.end(), {a, b, d, a, d, c});
            else
                m.indices.insert(m.indices.end(), {a, b, c, b, d, c});
        }
    return m;
}

WindowMesh fan(glm::vec2 centre, float radius, int n) {
    WindowMesh m;
    m.positions.push_back({centre.x, centre.y, 0.5f});
    for (int i = 0; i < n; ++i) {
        const double a = 2.0 * std::numbers::pi * i / n;
        m.positions.push_back({centre.x + radius * float(std::cos(a)), centre.y + radius * float(std::sin(a)),
                               0.5f});
    }
    for (int i = 0; i < n; ++i)
        m.indices.insert(m.indices.end(), {0u, uint32_t(1 + i), uint32_t(1 + (i + 1) % n)});
    return m;
}

Mesh sphere(int segments, int rings) {
    Mesh mesh;
    for (int r = 0; r <= rings; ++r)
        for (int s = 0; s <= segments; ++s) {
            const float u = float(s) / float(segments), v = float(r) / float(rings);
            const float theta = 2.0f * std::numbers::pi_v<float> * u, phi = std::numbers::pi_v<float> * v;
            // n = (cos 2pi u sin pi v, sin 2pi u sin pi v, cos pi v), p = c + R n.
            const glm::vec3 n(std::cos(theta) * std::sin(phi), std::sin(theta) * std::sin(phi), std::cos(phi));
            mesh.positions.push_back(n);
            mesh.normals.push_back(n);
            mesh.uvs.push_back({u, v});
        }
    const uint32_t row = uint32_t(segments + 1);
    for (int r = 0; r < rings; ++r)
        for (int s = 0; s < segments; ++s) {
            const uint32_t a = uint32_t(r) * row + uint32_t(s), b = a + 1, c = a + row, d = c + 1;
            if (r > 0) mesh.indices.insert(mesh.indices.end(), {a, c, b});
            if (r < rings - 1) mesh.indices.insert(mesh.indices.end(), {b, c, d});
        }
    return mesh;
}

}  // namespace tessera::workloads
