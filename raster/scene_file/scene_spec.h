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
#include "raster/geometry/snake.h"
#include "raster/render/animated_scene.h"
#include "raster/scene/light.h"
#include "raster/scene/material.h"
#include "raster/scene/transform.h"
#include "raster/scene/background.h"
#include "raster/texture/texture.h"

namespace tessera::scene_file {

struct TextureSpec {
    enum class Kind { file, reaction_diffusion, relief_normals };
    std::string name;
    Kind kind = Kind::file;
    // file
    std::filesystem::path file;  // relative paths are resolved against the scene file
    texture::TexelEncoding encoding = texture::TexelEncoding::srgb;
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
    // relief_normals: a tangent-space normal map of a procedural heightfield (bump mapping)
    procedural::HeightfieldParams relief;
    float strength = 8.0f;
};

struct MaterialSpec {
    std::string name;
    scene::Material material;             // parameters already applied (set_material_parameters)
    std::string diffuse_texture;   // TextureSpec names; empty: none
    std::string normal_texture;
};

struct HeightfieldSpec {
    procedural::HeightfieldParams relief;
    glm::ivec2 samples{129, 129};  // grid vertices along x and z
    glm::vec2 size{10.0f, 10.0f};  // world extent along x and z
    float height = 1.0f;           // world height of relief value 1
};

// A snake: its shape and motion (geometry/snake.h), the heightfield object it lies on and the
// material of its eyes.
struct SnakeSpec : geometry::SnakeShape {
    std::string ground;        // a heightfield object to lie on; empty: the plane y = transform.translate.y
    std::string eye_material;  // empty: the body's
};

struct ObjectSpec {
    enum class Shape { sphere, ellipsoid, torus, flag, box, heightfield, snake, mesh };
    std::string name;
    Shape shape = Shape::sphere;
    std::string material;
    scene::Transform transform;
    glm::vec3 spin_axis{0.0f, 1.0f, 0.0f};
    float spin = 0.0f;  // rad/s about spin_axis, after the transform's own rotation
    glm::ivec2 tessellation{48, 24};
    // sphere / ellipsoid / torus
    glm::vec3 centre{0.0f};
    float radius = 1.0f;
    glm::vec3 radii{1.0f};
    float major = 1.0f, minor = 0.3f;
    // flag (the waving flag: phase = wave_speed * time)
    glm::vec2 flag_size{2.0f, 1.2f};
    float flag_depth = 0.1f, flag_waves = 3.0f, wave_speed = 3.0f;
    // box: an axis-aligned box of `box_size` centred on the origin (geometry/box.h: one quad
    // per face; `tessellation` does not apply)
    glm::vec3 box_size{1.0f};
    HeightfieldSpec heightfield;
    SnakeSpec snake;
    // mesh: a model file (OBJ + MTL, glTF 2.0, PLY, ... through raster/asset/model_import.h;
    // relative paths resolve against the scene file) with its own materials, or every part in
    // `material` when that is set
    std::filesystem::path file;
};

struct AnimationSpec {
    float fps = 24.0f;
    int first = 1, last = 48;  // the default --frames
};

struct SceneSpec {
    std::filesystem::path file;  // where it was read from (relative paths resolve against it)
    std::string description;
    render::CameraSpec camera;
    bool camera_given = false;  // else build_scene frames the scene's objects (asset/framing.h)
    scene::Background background;
    std::vector<scene::Light> lights;
    bool lights_given = false;  // else build_scene lights it with the default rig (asset/light_rig.h)
    std::vector<TextureSpec> textures;
    std::vector<MaterialSpec> materials;
    std::vector<ObjectSpec> objects;
    std::vector<render::PassSpec> passes;
    AnimationSpec animation;
    glm::ivec2 size{1280, 720};   // the default --size
    std::string shadows = "none";  // the default --shadows
    int samples = 1;               // the default --samples (pipeline/sample_pattern.h)
};

}  // namespace tessera::scene_file
