#include "raster/shadow/cascades.h"

#include <glm/gtc/matrix_transform.hpp>
#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <cmath>

namespace tessera::shadow {
namespace {

std::array<glm::vec3, 8> corners_of(const Bounds& b) {
    std::array<glm::vec3, 8> c;
    for (int i = 0; i < 8; ++i)
        c[size_t(i)] = {i & 1 ? b.hi.x : b.lo.x, i & 2 ? b.hi.y : b.lo.y, i & 4 ? b.hi.z : b.lo.z};
    return c;
}

// The camera's frame: right u, up v, and backward w (the view looks along -w), as view().
struct CameraFrame {
    glm::vec3 u, v, w;
};
CameraFrame frame_of(const Camera& camera) {
    const glm::vec3 w = glm::normalize(camera.eye - camera.lookat);
    const glm::vec3 u = glm::normalize(glm::cross(camera.up, w));
    return {u, glm::cross(w, u), w};
}

// Corners of the slice in the camera's space (x right, y up, looking down -z).
std::array<glm::vec3, 8> camera_space_slice(const Camera& camera, float d0, float d1) {
    const float ty = std::tan(glm::radians(camera.fovy_deg) * 0.5f), tx = ty * camera.aspect;
    std::array<glm::vec3, 8> c;
    for (int i = 0; i < 8; ++i) {
        const float d = i < 4 ? d0 : d1;
        const float x = i & 1 ? camera.window.x_high : camera.window.x_low;
        const float y = i & 2 ? camera.window.y_high : camera.window.y_low;
        c[size_t(i)] = {x * tx * d, y * ty * d, -d};
    }
    return c;
}

}  // namespace

Bounds mesh_bounds(const Mesh& mesh) {
    // min/max: the same whatever the split.
    return tbb::parallel_reduce(
        tbb::blocked_range<size_t>(0, mesh.vertex_count(), 1 << 15), Bounds{},
        [&](const tbb::blocked_range<size_t>& range, Bounds b) {
            for (size_t v = range.begin(); v != range.end(); ++v) {
                const glm::vec3& p = mesh.positions[v];
                if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) continue;
                b.lo = glm::min(b.lo, p);
                b.hi = glm::max(b.hi, p);
            }
            return b;
        },
        [](Bounds a, const Bounds& b) {
            a.lo = glm::min(a.lo, b.lo);
            a.hi = glm::max(a.hi, b.hi);
            return a;
        });
}

std::vector<float> cascade_splits(float near, float far, int count, float blend) {
    std::vector<float> splits(size_t(count) + 1);
    for (int i = 0; i <= count; ++i) {
        const float t = float(i) / float(count);
        const float logarithmic = near * std::pow(far / near, t);
        const float uniform = near + (far - near) * t;
        splits[size_t(i)] = blend * logarithmic + (1.0f - blend) * uniform;
    }
    splits.front() = near;
    splits.back() = far;
    return splits;
}

std::array<float, 2> shadowed_depths(const Camera& camera, const Bounds& scene) {
    const float near = camera.near, far = camera.far;
    if (scene.empty()) return {near, near};
    const glm::vec3 forward = -frame_of(camera).w;
    float nearest = std::numeric_limits<float>::infinity(), farthest = -nearest;
    for (const glm::vec3& c : corners_of(scene)) {
        const float depth = glm::dot(c - camera.eye, forward);
        nearest = std::min(nearest, depth);
        farthest = std::max(farthest, depth);
    }
    if (!(farthest > near)) return {near, near};
    // On the grid near * 2^(k/8): the ends move only when the scene's extent crosses a step.
    constexpr float kSteps = 8.0f;
    const auto on_grid = [&](float depth, bool up) {
        const float k = kSteps * std::log2(depth / near);
        return near * std::exp2((up ? std::ceil(k) : std::floor(k)) / kSteps);
    };
    const float first = nearest > near ? std::min(on_grid(nearest, false), far) : near;
    const float last = std::min(on_grid(farthest, true), far);
    return {first, std::max(first, last)};
}

std::array<glm::vec3, 8> frustum_slice(const Camera& camera, float d0, float d1) {
    const CameraFrame f = frame_of(camera);
    std::array<glm::vec3, 8> corners = camera_space_slice(camera, d0, d1);
    for (glm::vec3& c : corners) c = camera.eye + c.x * f.u + c.y * f.v + c.z * f.w;
    return corners;
}

Sphere slice_sphere(const Camera& camera, float d0, float d1) {
    // The slice's corners at depth d lie d * k from the line through the window's centre
    // (k: the window's half diagonal at unit depth). On that line, the point equally far
    // from the near and the far corners is at depth (d0 + d1)(1 + k^2) / 2 (a right
    // frustum's smallest enclosing sphere), or the far end if that lies beyond it. The radius
    // is the largest distance to a corner, so the sphere covers the slice whatever the window.
    const float ty = std::tan(glm::radians(camera.fovy_deg) * 0.5f), tx = ty * camera.aspect;
    const Camera::Window& w = camera.window;
    const float hx = 0.5f * (w.x_high - w.x_low) * tx, hy = 0.5f * (w.y_high - w.y_low) * ty;
    const float cx = 0.5f * (w.x_high + w.x_low) * tx, cy = 0.5f * (w.y_high + w.y_low) * ty;
    const float k2 = hx * hx + hy * hy;
    const float depth = std::min(0.5f * (d0 + d1) * (1.0f + k2), d1);
    Sphere s;
    s.centre = {cx * depth, cy * depth, -depth};
    for (const glm::vec3& c : camera_space_slice(camera, d0, d1))
        s.radius = std::max(s.radius, glm::length(c - s.centre));
    const CameraFrame f = frame_of(camera);
    s.centre = camera.eye + s.centre.x * f.u + s.centre.y * f.v + s.centre.z * f.w;
    return s;
}

Sphere bounds_sphere(const Bounds& scene) {
    if (scene.empty()) return {glm::vec3(0.0f), 1.0f};
    return {0.5f * (scene.lo + scene.hi), std::max(0.5f * glm::length(scene.hi - scene.lo), 1e-6f)};
}

LightProjection fit_distant_light(const glm::vec3& towards_light, const Sphere& sphere,
                                  const Bounds& scene, int resolution) {
    LightProjection p;
    p.axis = -glm::normalize(towards_light);
    const glm::vec3 up = std::abs(p.axis.y) > 0.99f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
    // A rotation only: the light's frame does not depend on the camera, so snapping in it
    // is snapping on a fixed world grid.
    const glm::mat4 view = glm::lookAtRH(glm::vec3(0.0f), p.axis, up);
    const float radius = std::max(sphere.radius, 1e-6f);
    p.texel_size = 2.0f * radius / float(resolution);
    const float half = 0.5f * p.texel_size * float(resolution);
    const glm::vec3 centre = glm::vec3(view * glm::vec4(sphere.centre, 1.0f));
    const float x = std::floor(centre.x / p.texel_size) * p.texel_size;
    const float y = std::floor(centre.y / p.texel_size) * p.texel_size;
    // Depths along the light (-z of its view): casters from the scene's near side, receivers
    // up to the sphere's far side.
    float near = -centre.z - radius, far = -centre.z + radius;
    if (!scene.empty()) {
        float lo = std::numeric_limits<float>::infinity();
        for (const glm::vec3& c : corners_of(scene)) lo = std::min(lo, -(view * glm::vec4(c, 1.0f)).z);
        near = std::min(near, lo);
    }
    const float margin = 1e-3f * (far - near) + p.texel_size;
    const glm::mat4 projection = glm::orthoRH_NO(x - half, x + half, y - half, y + half, near - margin, far + margin);
    p.view_projection = projection * view;
    return p;
}

LightProjection fit_point_light(const glm::vec3& light, const Sphere& sphere, const Bounds& scene,
                                int resolution) {
    LightProjection p;
    const float radius = std::max(sphere.radius, 1e-6f);
    float distance = glm::length(sphere.centre - light);
    Camera camera;
    camera.eye = light;
    // Looking at the centre; from inside the sphere (or on it) any direction will do.
    camera.lookat = distance > 1e-6f * radius ? sphere.centre : light + glm::vec3(0, -1, 0);
    distance = std::max(distance, 1e-6f * radius);
    p.axis = glm::normalize(camera.lookat - light);
    camera.up = std::abs(p.axis.y) > 0.99f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
    camera.aspect = 1.0f;
    const bool outside = distance > 1.01f * radius;
    camera.fovy_deg = outside ? glm::degrees(2.0f * std::asin(radius / distance)) * 1.02f : 120.0f;
    camera.far = distance + radius;
    // Near at the scene's closest point (casters in front of the sphere), but not so close
    // that depth precision collapses.
    const Sphere all = bounds_sphere(scene);
    const float scene_near = scene.empty() ? distance - radius : glm::length(all.centre - light) - all.radius;
    camera.near = std::max(std::min(scene_near, distance - radius), camera.far * 1e-3f);
    p.view_projection = camera.view_projection();
    p.texel_per_depth = 2.0f * std::tan(glm::radians(camera.fovy_deg) * 0.5f) / float(resolution);
    return p;
}

}  // namespace tessera::shadow
