// The small scenes of the shading goldens, shared by the golden tests (brute-force visibility)
// and the frame-path tests (the same scenes through FrameRenderer's tile rasterizer).
#pragma once
#include <glm/gtc/constants.hpp>

#include <memory>
#include <vector>

#include "raster/geometry/param_surface.h"
#include "raster/geometry/surfaces.h"
#include "raster/scene/scene.h"

namespace tessera::test {

// A material lit only by its own colour where ambient and diffuse light add to one: kd and
// ka both `kd`, no highlight.
inline scene::Material flat_colour(glm::vec3 kd) {
    scene::Material m;
    m.kd = kd;
    m.ka = kd;
    m.ks = glm::vec3(0.0f);
    return m;
}

inline scene::Scene base_scene(scene::Material material) {
    scene::Scene s;
    s.camera.eye = {0.0f, 0.6f, 3.2f};
    s.camera.lookat = {0.0f, 0.0f, 0.0f};
    s.camera.fovy_deg = 45.0f;
    s.camera.aspect = 1.0f;
    s.background.colour = {0.05f, 0.05f, 0.08f};
    s.lights = {scene::point_light({2.0f, 2.5f, 3.0f}, glm::vec3(0.15f), glm::vec3(1.0f))};
    s.materials = {material};
    s.objects = {scene::Object{"sphere", std::make_shared<const Mesh>(geometry::tessellate(geometry::sphere_surface({0, 0, 0}, 1.0f), 20, 10)),
                        0, {}, {}}};
    // The parametric sphere has its poles on z; turn them to y so the pole row is not head-on.
    s.objects[0].transform.axis = {1, 0, 0};
    s.objects[0].transform.angle = -glm::half_pi<float>();
    return s;
}

inline scene::Material coloured(scene::ShadingModel model) {
    scene::Material m;
    m.model = model;
    m.ka = {0.8f, 0.3f, 0.2f};
    m.kd = {0.8f, 0.3f, 0.2f};
    m.ks = glm::vec3(0.6f);
    m.shine = 40.0f;
    return m;
}

// The Phong sphere with a thin glass torus in front of it: the torus's near and far sides
// both blend over the sphere, in submission order.
inline scene::Scene transparent_scene() {
    scene::Scene s = base_scene(coloured(scene::ShadingModel::phong));
    scene::Material glass = coloured(scene::ShadingModel::phong);
    glass.kd = glass.ka = {0.2f, 0.5f, 0.9f};
    glass.opacity = 0.4f;
    s.materials.push_back(glass);
    s.objects.push_back(scene::Object{"ring", std::make_shared<const Mesh>(geometry::tessellate(geometry::torus_surface(1.2f, 0.15f), 32, 8)),
                               1, {}, {}});
    s.objects[1].transform.axis = {1, 0, 0};
    s.objects[1].transform.angle = 0.5f;
    s.objects[1].transform.translation = {0, 0, 0.6f};
    return s;
}

inline texture::Texture checker_texture() {
    std::vector<glm::vec4> t(64 * 32);
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 64; ++x)
            t[size_t(y * 64 + x)] = ((x / 8 + y / 8) & 1) ? glm::vec4(0.9f, 0.85f, 0.7f, 1) : glm::vec4(0.1f, 0.3f, 0.6f, 1);
    return texture::Texture(64, 32, std::move(t));
}

// A tangent-space normal map of round bumps, analytic: h = sin(2 pi 8 u) sin(2 pi 4 v) * 0.04
// over a 1 x 1 uv square, n = normalize(-dh/du, -dh/dv, 1) (u and v in texture units).
inline texture::Texture bump_map() {
    const int w = 128, h = 64;
    const float pi = glm::pi<float>(), a = 0.04f;
    std::vector<glm::vec4> t(size_t(w * h));
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const float u = (x + 0.5f) / w, v = (y + 0.5f) / h;
            const float du = a * 16 * pi * std::cos(16 * pi * u) * std::sin(8 * pi * v);
            const float dv = a * 8 * pi * std::sin(16 * pi * u) * std::cos(8 * pi * v);
            const glm::vec3 n = glm::normalize(glm::vec3(-du, -dv, 1.0f));
            t[size_t(y * w + x)] = glm::vec4(n * 0.5f + 0.5f, 1.0f);
        }
    return texture::Texture(w, h, std::move(t));
}

}  // namespace tessera::test
