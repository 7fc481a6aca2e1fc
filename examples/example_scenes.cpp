#include "examples/example_scenes.h"

#include <glm/gtc/constants.hpp>

#include <cmath>
#include <stdexcept>

#include "examples/example_textures.h"
#include "raster/geometry/box.h"
#include "raster/geometry/param_surface.h"
#include "raster/geometry/surfaces.h"
#include "raster/obj_loader.h"

namespace tessera::examples {
namespace {

constexpr float kTwoPi = 2.0f * glm::pi<float>();

std::shared_ptr<const Mesh> shared(Mesh mesh) { return std::make_shared<const Mesh>(std::move(mesh)); }

}  // namespace

std::vector<std::string> scene_names() { return {"flag", "toon", "bumpcube", "snakes"}; }

Scene make_scene(std::string_view name) {
    if (name == "flag") return flag_scene();
    if (name == "toon") return toon_scene();
    if (name == "bumpcube") return bumpcube_scene();
    if (name == "snakes") return snakes_scene();
    std::string names;
    for (const std::string& n : scene_names()) names += (names.empty() ? "" : ", ") + n;
    throw std::invalid_argument("unknown scene '" + std::string(name) + "'; valid scenes: " + names);
}

Scene flag_scene() {
    Scene s;
    s.camera.eye = {0.0f, 0.9f, 5.2f};
    s.camera.lookat = {0.0f, 0.65f, 0.0f};
    s.camera.fovy_deg = 40.0f;
    s.background.kind = Background::Kind::sky;
    s.lights = {point_light({0.0f, 2.0f, 2.5f}, glm::vec3(0.12f), glm::vec3(1.0f))};
    Material cloth;
    cloth.ka = cloth.kd = {0.75f, 0.12f, 0.10f};
    cloth.ks = glm::vec3(0.8f);
    cloth.shine = 120.0f;
    cloth.model = ShadingModel::gouraud;
    s.materials.push_back(cloth);
    cloth.model = ShadingModel::phong;
    s.materials.push_back(cloth);
    // The seed's flag p = (u W, v H, sin(K pi u + phase) D), the phase advancing with time.
    const auto wave = [](Object& o, float t) {
        o.geometry = shared(tessellate(flag_surface(2.0f, 1.3f, 0.15f, 3.0f, kTwoPi * 0.5f * t), 16, 6));
    };
    for (uint32_t i = 0; i < 2; ++i) {
        Object flag{i == 0 ? "gouraud flag" : "phong flag", nullptr, i, {}, wave};
        flag.transform.translation = {i == 0 ? -2.15f : 0.15f, 0.0f, 0.0f};
        flag.animate(flag, 0.0f);
        s.objects.push_back(std::move(flag));
    }
    return s;
}

Scene toon_scene() {
    Scene s;
    s.camera.eye = {0.0f, 1.2f, 5.0f};
    s.camera.fovy_deg = 45.0f;
    s.background.colour = {0.95f, 0.93f, 0.85f};
    s.lights = {directional_light({1.0f, 1.5f, 1.0f}, glm::vec3(0.0f), glm::vec3(1.0f))};
    const glm::vec3 colours[3] = {{0.9f, 0.35f, 0.2f}, {0.2f, 0.55f, 0.9f}, {0.4f, 0.8f, 0.3f}};
    for (const glm::vec3& c : colours) {
        Material m;
        m.model = ShadingModel::toon;
        m.kd = c;
        s.materials.push_back(m);
    }
    s.objects.push_back(Object{"sphere", shared(tessellate(sphere_surface({0, 0, 0}, 0.8f), 48, 24)), 0, {}, {}});
    s.objects[0].transform.translation = {-1.6f, 0.0f, 0.0f};
    Object torus{"torus", shared(tessellate(torus_surface(0.75f, 0.28f), 64, 24)), 1, {}, {}};
    torus.animate = [](Object& o, float t) {
        o.transform.axis = {1.0f, 0.3f, 0.0f};
        o.transform.angle = 0.9f + 0.8f * t;
    };
    torus.animate(torus, 0.0f);
    s.objects.push_back(std::move(torus));
    Object egg{"ellipsoid", shared(tessellate(ellipsoid_surface({0, 0, 0}, {0.5f, 0.9f, 0.5f}), 48, 24)), 2, {}, {}};
    egg.transform.translation = {1.6f, 0.0f, 0.0f};
    egg.transform.axis = {0, 0, 1};
    egg.transform.angle = -0.4f;
    s.objects.push_back(std::move(egg));
    return s;
}

Scene bumpcube_scene() {
    Scene s;
    s.camera.eye = {0.0f, 1.6f, 4.2f};
    s.camera.fovy_deg = 40.0f;
    s.background.kind = Background::Kind::sky;
    s.lights = {point_light({2.5f, 3.0f, 3.5f}, glm::vec3(0.15f), glm::vec3(0.9f)),
                directional_light({-1.0f, 0.4f, 0.8f}, glm::vec3(0.0f), glm::vec3(0.25f, 0.25f, 0.3f))};
    s.textures.push_back(reaction_diffusion_texture("mitosis", 256, 2500, 7));
    s.textures.push_back(normal_map_texture(heightfield_grid(256, 11, 6), 12.0f));
    Material m;
    m.ka = m.kd = glm::vec3(1.0f);
    m.ks = glm::vec3(0.35f);
    m.shine = 24.0f;
    m.diffuse_texture = 0;
    m.normal_texture = 1;
    s.materials.push_back(m);
    Object cube{"cube", shared(box_mesh(glm::vec3(0.9f))), 0, {}, {}};
    cube.animate = [](Object& o, float t) {
        o.transform.axis = {0.3f, 1.0f, 0.15f};
        o.transform.angle = 0.6f + 0.5f * t;
    };
    cube.animate(cube, 0.0f);
    s.objects.push_back(std::move(cube));
    return s;
}

Scene obj_scene(const std::string& path, ShadingModel model) {
    auto mesh = std::make_shared<Mesh>(load_obj(path));
    glm::vec3 lo(INFINITY), hi(-INFINITY);
    for (const glm::vec3& p : mesh->positions) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    Scene s;
    s.camera.eye = {0.0f, 0.4f, 3.2f};
    s.camera.fovy_deg = 40.0f;
    s.background.kind = Background::Kind::sky;
    s.lights = {point_light({2.0f, 3.0f, 3.0f}, glm::vec3(0.12f), glm::vec3(0.9f)),
                directional_light({-1.0f, 0.3f, 0.5f}, glm::vec3(0.0f), glm::vec3(0.3f))};
    Material m;
    m.model = model;
    m.ka = m.kd = {0.8f, 0.55f, 0.35f};
    if (!mesh->uvs.empty() && model != ShadingModel::gouraud) {
        std::vector<glm::vec4> texels(64 * 64);
        for (int y = 0; y < 64; ++y)
            for (int x = 0; x < 64; ++x)
                texels[size_t(y * 64 + x)] = ((x / 8 + y / 8) & 1) ? glm::vec4(1.0f) : glm::vec4(0.55f, 0.6f, 0.7f, 1.0f);
        s.textures.emplace_back(64, 64, std::move(texels));
        m.diffuse_texture = 0;
    }
    s.materials.push_back(m);
    Object o{"mesh", std::move(mesh), 0, {}, {}};
    const float radius = 0.5f * glm::length(hi - lo);
    if (radius > 0.0f && std::isfinite(radius)) {
        o.transform.scale = glm::vec3(1.0f / radius);
        o.transform.translation = -0.5f * (lo + hi) / radius;
    }
    s.objects.push_back(std::move(o));
    return s;
}

}  // namespace tessera::examples
