// The "writhing snakes" homework of seeds/000, built from the pieces it names: per-pixel Phong;
// bodies = extruded surfaces along a spline spine with an elliptical profile; heads and eyes =
// ellipsoids; material = reaction-diffusion textured diffuse + white Blinn-Phong specular;
// animation = spine control points moving on closed curves with different periods; sand = a
// procedural heightfield.
#include <glm/gtc/constants.hpp>

#include <array>
#include <cmath>

#include "examples/example_scenes.h"
#include "examples/example_textures.h"
#include "procedural/heightfield.h"
#include "raster/geometry/extrusion.h"
#include "raster/geometry/param_surface.h"
#include "raster/geometry/surfaces.h"

namespace tessera::examples {
namespace {

namespace tp = tessera::procedural;
constexpr float kTwoPi = 2.0f * glm::pi<float>();
constexpr int kControlPoints = 9;
constexpr glm::vec2 kSandSize{12.0f, 12.0f};
constexpr float kSandHeight = 0.35f;

// The sand as a height function of (x, z): bilinear over the grid, matching the mesh that
// heightfield_surface() builds from it.
struct Sand {
    std::shared_ptr<const tp::Grid> grid;
    float height(float x, float z) const {
        const float fx = std::clamp((x / kSandSize.x + 0.5f) * float(grid->width - 1), 0.0f, float(grid->width - 1));
        const float fz = std::clamp((z / kSandSize.y + 0.5f) * float(grid->height - 1), 0.0f, float(grid->height - 1));
        const int x0 = std::min(int(fx), grid->width - 2), z0 = std::min(int(fz), grid->height - 2);
        const float ax = fx - float(x0), az = fz - float(z0);
        const float h0 = glm::mix(grid->at(x0, z0), grid->at(x0 + 1, z0), ax);
        const float h1 = glm::mix(grid->at(x0, z0 + 1), grid->at(x0 + 1, z0 + 1), ax);
        return glm::mix(h0, h1, az) * kSandHeight;
    }
};

struct SnakeParams {
    glm::vec2 centre;
    float heading;      // radians, direction from tail to head in the xz plane
    float length;
    float period;       // seconds per undulation
    float phase;
};

// The spine's control points at time t: a lateral travelling wave (the slither) plus a small
// circle per point, each point with its own period, so every point runs on a closed curve.
std::array<glm::vec3, kControlPoints> control_points(const SnakeParams& p, const Sand& sand, float t) {
    std::array<glm::vec3, kControlPoints> points;
    const glm::vec2 forward(std::cos(p.heading), std::sin(p.heading)), side(-forward.y, forward.x);
    for (int j = 0; j < kControlPoints; ++j) {
        const float s = float(j) / float(kControlPoints - 1);  // 0 at the head
        const float wave = 0.22f * std::sin(kTwoPi * (1.3f * s - t / p.period) + p.phase);
        const float wobble_period = p.period * (0.7f + 0.11f * float(j));
        const float angle = kTwoPi * t / wobble_period + float(j);
        const glm::vec2 xz = p.centre + forward * ((0.5f - s) * p.length) + side * wave +
                             0.05f * glm::vec2(std::cos(angle), std::sin(angle));
        points[size_t(j)] = {xz.x, sand.height(xz.x, xz.y) + 0.08f, xz.y};
    }
    return points;
}

BezierCurve<glm::vec3> spine_at(const SnakeParams& p, const Sand& sand, float t) {
    const auto points = control_points(p, sand, t);
    return catmull_rom<glm::vec3>(points);
}

// Semi-axes (vertical a, sideways b) from the neck (s = 0) to the pointed tail (s = 1).
const BezierCurve<glm::vec2>& body_profile() {
    static const std::array<glm::vec2, 6> radii = {
        {{0.070f, 0.095f}, {0.095f, 0.130f}, {0.100f, 0.135f}, {0.085f, 0.110f}, {0.050f, 0.065f}, {0.0f, 0.0f}}};
    static const BezierCurve<glm::vec2> profile = catmull_rom<glm::vec2>(radii);
    return profile;
}

// Where the head sits and where it looks: just before the spine's start, facing away from it.
struct HeadPose {
    glm::vec3 centre, forward, side;
};
HeadPose head_pose(const BezierCurve<glm::vec3>& spine) {
    const glm::vec3 forward = -glm::normalize(spine.derivative(0.0f));
    const glm::vec3 side = glm::normalize(glm::cross(glm::vec3(0, 1, 0), forward));
    return {spine.position(0.0f) + forward * 0.1f + glm::vec3(0, 0.01f, 0), forward, side};
}

// Rotation taking +x to `forward` (the ellipsoid's long axis).
void face(Transform& transform, glm::vec3 forward) {
    const glm::vec3 axis = glm::cross(glm::vec3(1, 0, 0), forward);
    const float sine = glm::length(axis), cosine = forward.x;
    transform.axis = sine > 1e-6f ? axis / sine : glm::vec3(0, 1, 0);
    transform.angle = std::atan2(sine, cosine);
}

}  // namespace

Scene snakes_scene() {
    Scene s;
    s.camera.eye = {0.2f, 1.7f, 3.4f};
    s.camera.lookat = {0.1f, 0.15f, 0.4f};
    s.camera.fovy_deg = 42.0f;
    const glm::vec3 sun(0.5f, 0.9f, 0.35f);
    s.background.kind = Background::Kind::sky;
    s.background.sky.sun_direction = sun;
    s.lights = {directional_light(sun, glm::vec3(0.25f), glm::vec3(1.0f, 0.95f, 0.85f))};

    // Sand: procedural dunes.
    tp::HeightfieldParams dunes;
    dunes.relief = tp::Relief::dunes;
    dunes.cells = 3;
    dunes.fractal.seed = 5;
    auto grid = std::make_shared<const tp::Grid>(tp::generate_heightfield(192, 192, dunes));
    const Sand sand{grid};
    Material sand_material;
    sand_material.ka = sand_material.kd = {0.76f, 0.62f, 0.42f};
    sand_material.ks = glm::vec3(0.05f);
    sand_material.shine = 8.0f;
    s.materials.push_back(sand_material);
    s.objects.push_back(Object{"sand",
                               std::make_shared<const Mesh>(tessellate(
                                   heightfield_surface(grid->values, grid->width, grid->height, kSandSize, kSandHeight),
                                   grid->width - 1, grid->height - 1)),
                               0, {}, {}});

    Material eye;
    eye.ka = eye.kd = glm::vec3(0.02f);
    eye.ks = glm::vec3(0.9f);
    eye.shine = 120.0f;
    s.materials.push_back(eye);
    const uint32_t eye_material = 1;

    const std::array<SnakeParams, 3> snakes = {{{{-1.2f, 0.5f}, 0.35f, 2.6f, 2.2f, 0.0f},
                                                {{1.5f, -1.0f}, 2.8f, 2.3f, 1.7f, 1.3f},
                                                {{0.4f, 1.7f}, -0.2f, 2.0f, 2.7f, 2.4f}}};
    const std::array<const char*, 3> skins = {"spots", "stripes", "worms"};
    for (size_t k = 0; k < snakes.size(); ++k) {
        s.textures.push_back(reaction_diffusion_texture(skins[k], 128, 2000, uint32_t(17 + k)));
        Material skin;
        skin.ka = glm::vec3(0.3f, 0.28f, 0.25f);
        skin.kd = glm::vec3(1.0f);
        skin.ks = glm::vec3(0.6f);  // white Blinn-Phong highlights
        skin.shine = 50.0f;
        skin.diffuse_texture = int32_t(k);
        skin.uv_scale = {7.0f, 1.0f};  // the tileable skin repeats along the body
        s.materials.push_back(skin);
        const uint32_t skin_material = uint32_t(s.materials.size() - 1);
        const SnakeParams p = snakes[k];

        Object body{"snake body", nullptr, skin_material, {}, {}};
        body.animate = [p, sand](Object& o, float t) {
            o.geometry = std::make_shared<const Mesh>(extrude(spine_at(p, sand, t), body_profile(), 160, 20));
        };
        Object head{"snake head", std::make_shared<const Mesh>(tessellate(
                                      ellipsoid_surface({0, 0, 0}, {0.19f, 0.085f, 0.125f}), 32, 16)),
                    skin_material, {}, {}};
        head.animate = [p, sand](Object& o, float t) {
            const HeadPose pose = head_pose(spine_at(p, sand, t));
            face(o.transform, pose.forward);
            o.transform.translation = pose.centre;
        };
        const auto eye_mesh = std::make_shared<const Mesh>(tessellate(sphere_surface({0, 0, 0}, 0.028f), 12, 6));
        for (float side : {-1.0f, 1.0f}) {
            Object e{"snake eye", eye_mesh, eye_material, {}, {}};
            e.animate = [p, sand, side](Object& o, float t) {
                const HeadPose pose = head_pose(spine_at(p, sand, t));
                o.transform.translation = pose.centre + pose.forward * 0.09f + pose.side * (side * 0.075f) +
                                          glm::vec3(0, 0.05f, 0);
            };
            s.objects.push_back(std::move(e));
        }
        s.objects.push_back(std::move(body));
        s.objects.push_back(std::move(head));
    }
    s.animate(0.0f);
    return s;
}

}  // namespace tessera::examples
