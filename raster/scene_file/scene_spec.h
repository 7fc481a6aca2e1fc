// What a scene file describes, as plain data: the result of reading and checking the JSON
// (scene_parse.h) before any heavy work. Building the renderable scene from it (generating
// textures by reaction-diffusion, heightfields, tessellating) is scene_build.h's job, so
// parsing stays fast and testable on its own.
#pragma once
#include <glm/glm.hpp>

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "procedural/heightfield.h"
#include "procedural/rd_color.h"
#include "raster/camera.h"
#include "raster/march/fog.h"
#include "raster/march/march_settings.h"
#include "raster/march/metaball_field.h"
#include "raster/march/surface_shading.h"
#include "raster/scene/light.h"
#include "raster/scene/material.h"
#include "raster/scene/transform.h"
#include "raster/shade/background.h"
#include "raster/texture/texture.h"

namespace tessera {

// A camera pose at a time; between keys eye, lookat and fov follow a Catmull-Rom spline
// (C1, passes through every key), before the first and after the last they hold.
struct CameraKey {
    float time = 0.0f;  // seconds
    glm::vec3 eye{0.0f, 0.0f, 3.0f};
    glm::vec3 lookat{0.0f};
    float fovy_deg = 60.0f;
};

struct CameraSpec {
    Camera camera;               // the pose without keys; up, near, far always from here
    std::vector<CameraKey> keys;  // sorted by time, strictly increasing
    float orbit = 0.0f;          // rad/s: the eye circles the lookat point about +y
};

struct TextureSpec {
    enum class Kind { file, reaction_diffusion, relief_normals };
    std::string name;
    Kind kind = Kind::file;
    // file
    std::filesystem::path file;  // relative paths are resolved against the scene file
    TexelEncoding encoding = TexelEncoding::srgb;
    // reaction_diffusion: Gray-Scott from a preset, grown for `steps`, through `ramp`
    std::string preset = "spots";
    int size = 256;  // texels, square
    int steps = 4000;
    // Growing skin: the texture of frame f is the state after steps + grow_per_frame * f
    // steps (0: a static skin). Simulated state that depends on earlier frames, which the
    // render command advances frame by frame and checkpoints (farm/scene_simulation.h).
    int grow_per_frame = 0;
    uint32_t seed = 1;
    float anisotropy = 0.0f;
    std::vector<procedural::ColorStop> ramp;  // empty: the default snake-skin ramp
    // relief_normals: a tangent-space normal map of a procedural heightfield (seeds/004)
    procedural::HeightfieldParams relief;
    float strength = 8.0f;
};

struct MaterialSpec {
    std::string name;
    Material material;             // parameters already applied (set_material_parameters)
    std::string diffuse_texture;   // TextureSpec names; empty: none
    std::string normal_texture;
};

struct HeightfieldSpec {
    procedural::HeightfieldParams relief;
    glm::ivec2 samples{129, 129};  // grid vertices along x and z
    glm::vec2 size{10.0f, 10.0f};  // world extent along x and z
    float height = 1.0f;           // world height of relief value 1
};

// A snake of the seeds/000 homework. Its spine's control points ride a closed path (an
// ellipse around `centre`, turned by `path_angle`) at `speed` rad/s, spaced along it so the
// body spans `length`, and each sways sideways on its own closed curve: a sine of period
// wiggle_period * (1 + period_spread * i) and phase -wave_phase * i (a wave running from head
// to tail whose control points drift in and out of step: the writhing).
struct SnakeSpec {
    glm::vec2 centre{0.0f};
    glm::vec2 path_radii{2.0f, 1.5f};
    float path_angle = 0.0f;  // radians about +y
    float phase = 0.0f;       // the head's start angle on the path
    float speed = 0.25f;      // rad/s; negative: clockwise
    float length = 3.0f;
    float width = 0.12f;         // the body's largest horizontal semi-axis
    float height_ratio = 0.7f;   // vertical / horizontal semi-axis
    int control_points = 10;
    float wiggle = 0.22f;        // sideways sway amplitude
    float wiggle_period = 1.7f;  // seconds
    float period_spread = 0.11f;
    float wave_phase = 0.9f;     // radians per control point
    glm::ivec2 tessellation{192, 20};  // along the body, around it
    std::string ground;        // a heightfield object to lie on; empty: the plane y = transform.translate.y
    std::string eye_material;  // empty: the body's
};

struct ObjectSpec {
    enum class Shape { sphere, ellipsoid, torus, flag, box, heightfield, snake, mesh };
    std::string name;
    Shape shape = Shape::sphere;
    std::string material;
    Transform transform;
    glm::vec3 spin_axis{0.0f, 1.0f, 0.0f};
    float spin = 0.0f;  // rad/s about spin_axis, after the transform's own rotation
    glm::ivec2 tessellation{48, 24};
    // sphere / ellipsoid / torus
    glm::vec3 centre{0.0f};
    float radius = 1.0f;
    glm::vec3 radii{1.0f};
    float major = 1.0f, minor = 0.3f;
    // flag (seeds/000's waving flag: phase = wave_speed * time)
    glm::vec2 flag_size{2.0f, 1.2f};
    float flag_depth = 0.1f, flag_waves = 3.0f, wave_speed = 3.0f;
    // box: an axis-aligned box of `box_size` centred on the origin (geometry/box.h: one quad
    // per face; `tessellation` does not apply)
    glm::vec3 box_size{1.0f};
    HeightfieldSpec heightfield;
    SnakeSpec snake;
    // mesh: a Wavefront OBJ file (relative paths resolve against the scene file)
    std::filesystem::path file;
};

// Ray-marched compute passes (seeds/003), run per tile after rasterization in list order.
struct PassSpec {
    enum class Kind { terrain, metaballs, fog };
    Kind kind = Kind::terrain;
    // terrain: f = h(p.xz) - p.y with h from procedural/ (heightfield relief), marched
    procedural::TerrainParams terrain;
    // metaballs: `count` balls on Lissajous orbits (metaball_orbits.h), scaled and moved
    int count = 5;
    float ball_radius = 1.0f;
    float orbit_scale = 1.0f;
    glm::vec3 offset{0.0f};
    march::MetaballStyle style;
    march::MarchSettings settings;
    march::SurfaceMaterial material;
    march::Fog fog;  // fog
};

struct AnimationSpec {
    float fps = 24.0f;
    int first = 1, last = 48;  // the default --frames
};

struct SceneSpec {
    std::filesystem::path file;  // where it was read from (relative paths resolve against it)
    std::string description;
    CameraSpec camera;
    Background background;
    std::vector<Light> lights;
    std::vector<TextureSpec> textures;
    std::vector<MaterialSpec> materials;
    std::vector<ObjectSpec> objects;
    std::vector<PassSpec> passes;
    AnimationSpec animation;
    glm::ivec2 size{1280, 720};   // the default --size
    std::string shadows = "none";  // the default --shadows
};

}  // namespace tessera
