#include "raster/scene_file/scene_build.h"

#include <glm/gtc/quaternion.hpp>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>

#include <algorithm>
#include <exception>
#include <map>
#include <memory>
#include <optional>
#include <utility>

#include "procedural/field.h"
#include "procedural/normal_map.h"
#include "procedural/reaction_diffusion.h"
#include "raster/geometry/box.h"
#include "raster/geometry/param_surface.h"
#include "raster/geometry/surfaces.h"
#include "raster/asset/framing.h"
#include "raster/asset/light_rig.h"
#include "raster/asset/model_import.h"
#include "raster/core/direction.h"
#include "raster/scene_file/json_reader.h"
#include "raster/scene_file/rd_texture.h"
#include "raster/scene_file/scene_file_error.h"
#include "raster/geometry/snake.h"

namespace tessera::scene_file {
namespace {

namespace tp = tessera::procedural;

texture::Texture reaction_diffusion_texture(const TextureSpec& t) {
    tp::ReactionDiffusion rd = rd_simulation(t);
    rd.step(t.steps);
    return rd_texture(rd.state(), t);
}

texture::Texture relief_normal_texture(const TextureSpec& t) {
    const tp::Grid heights = tp::generate_heightfield(t.size, t.size, t.relief);
    const tp::NormalMap normals = tp::normal_map(heights, t.strength, tp::Boundary::periodic);
    std::vector<glm::vec4> texels(size_t(t.size) * size_t(t.size));
    for (size_t i = 0; i < texels.size(); ++i)
        texels[i] = glm::vec4(glm::vec3(normals.xyz[3 * i], normals.xyz[3 * i + 1], normals.xyz[3 * i + 2]) * 0.5f + 0.5f,
                              1.0f);
    return texture::Texture(t.size, t.size, std::move(texels));
}

texture::Texture build_texture(const TextureSpec& t, const std::filesystem::path& scene_file) {
    switch (t.kind) {
        case TextureSpec::Kind::reaction_diffusion: return reaction_diffusion_texture(t);
        case TextureSpec::Kind::relief_normals: return relief_normal_texture(t);
        case TextureSpec::Kind::file: break;
    }
    const std::filesystem::path path = t.file.is_absolute() ? t.file : scene_file.parent_path() / t.file;
    return texture::load_texture(path, t.encoding);
}

// Runs `build`; what the generators refuse (std::invalid_argument) and files that cannot be
// read (tessera::Error) become SceneFileError "FILE: POINTER: ...", naming the value in the
// scene file, so that a scene's content is never reported as a usage error.
template <class Build>
auto at_pointer(const SceneSpec& spec, const std::string& pointer, const Build& build) {
    try {
        return build();
    } catch (const SceneFileError&) {
        throw;
    } catch (const std::invalid_argument& e) {
        throw SceneFileError(spec.file.string() + ": " + pointer + ": " + e.what());
    } catch (const Error& e) {
        throw SceneFileError(spec.file.string() + ": " + pointer + ": " + e.what());
    }
}

// The scene's textures in its order. The generated ones are built side by side, one task
// each: a reaction-diffusion skin's steps then run on one thread instead of a fork and join of
// both threads per step (9,000 of them for the snakes' three skins), and a thread helps with
// a skin's rows only when it has nothing else to do. Files are read afterwards on this
// thread. The error reported is that of the first texture in the scene's order that fails,
// whatever the scheduling.
std::vector<texture::Texture> build_textures(const SceneSpec& spec) {
    const size_t count = spec.textures.size();
    auto build = [&](size_t i) {
        const TextureSpec& t = spec.textures[i];
        return at_pointer(spec, "/textures/" + JsonNode::escape(t.name), [&] { return build_texture(t, spec.file); });
    };
    std::vector<std::optional<texture::Texture>> built(count);
    std::vector<std::exception_ptr> failure(count);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, count, 1), [&](const tbb::blocked_range<size_t>& range) {
        for (size_t i = range.begin(); i < range.end(); ++i) {
            if (spec.textures[i].kind == TextureSpec::Kind::file) continue;
            try {
                built[i].emplace(build(i));
            } catch (...) {
                failure[i] = std::current_exception();
            }
        }
    }, tbb::simple_partitioner());
    std::vector<texture::Texture> textures;
    textures.reserve(count);
    for (size_t i = 0; i < count; ++i) {
        if (failure[i]) std::rethrow_exception(failure[i]);
        textures.push_back(built[i] ? std::move(*built[i]) : build(i));
    }
    return textures;
}

// A heightfield object's samples, kept for the snakes that lie on it.
struct Ground {
    tp::Grid heights;
    HeightfieldSpec spec;
    glm::vec3 offset{0.0f};

    // Bilinear in the samples, the same surface the triangles interpolate (up to the diagonal).
    float height(float x, float z) const {
        const float u = ((x - offset.x) / spec.size.x + 0.5f) * float(heights.width - 1);
        const float v = ((z - offset.z) / spec.size.y + 0.5f) * float(heights.height - 1);
        const float cu = std::clamp(u, 0.0f, float(heights.width - 1));
        const float cv = std::clamp(v, 0.0f, float(heights.height - 1));
        const int i = std::min(int(cu), heights.width - 2), j = std::min(int(cv), heights.height - 2);
        const float fu = cu - float(i), fv = cv - float(j);
        const float h = (heights.at(i, j) * (1 - fu) + heights.at(i + 1, j) * fu) * (1 - fv) +
                        (heights.at(i, j + 1) * (1 - fu) + heights.at(i + 1, j + 1) * fu) * fv;
        return offset.y + h * spec.height;
    }
};

// The transform's rotation followed by `spin` rad/s about `axis` after `time` seconds.
scene::Transform spun(const scene::Transform& base, glm::vec3 axis, float spin, float time) {
    scene::Transform t = base;
    // unit_direction: an axis of any length (checked non-zero when the scene was read).
    const glm::quat q = glm::angleAxis(spin * time, *unit_direction(axis)) *
                        (base.angle != 0.0f ? glm::angleAxis(base.angle, *unit_direction(base.axis)) : glm::quat(1, 0, 0, 0));
    t.angle = glm::angle(q);
    t.axis = t.angle != 0.0f ? glm::axis(q) : glm::vec3(0.0f, 1.0f, 0.0f);
    return t;
}

void set_rotation(scene::Transform& t, const glm::quat& q) {
    t.angle = glm::angle(q);
    t.axis = t.angle != 0.0f ? glm::axis(q) : glm::vec3(0.0f, 1.0f, 0.0f);
}

uint32_t material_index(const SceneSpec& spec, const std::string& name) {
    for (size_t i = 0; i < spec.materials.size(); ++i)
        if (spec.materials[i].name == name) return uint32_t(i);
    throw std::invalid_argument("material '" + name + "' is not defined");
}

// The object turning about its spin axis, after its own transform.
void add_spin(scene::Object& object, const ObjectSpec& o) {
    if (o.spin == 0.0f) return;
    const scene::Transform base = o.transform;
    const glm::vec3 axis = o.spin_axis;
    const float spin = o.spin;
    auto inner = object.animate;
    object.animate = [base, axis, spin, inner](scene::Object& self, float time) {
        if (inner) inner(self, time);
        self.transform = spun(base, axis, spin, time);
    };
}

// A model file's parts as objects, each placed by the object's transform; with its own
// materials and textures, or all in the object's material.
void add_model(scene::Scene& scene, const SceneSpec& spec, const ObjectSpec& o, const std::string& pointer,
               std::vector<std::string>* warnings) {
    const std::filesystem::path path = o.file.is_absolute() ? o.file : spec.file.parent_path() / o.file;
    asset::ImportedModel model = at_pointer(spec, pointer + "/file", [&] { return asset::import_model(path); });
    if (warnings)
        for (const std::string& w : model.warnings) warnings->push_back("object '" + o.name + "': " + w);
    std::optional<uint32_t> material;
    if (!o.material.empty()) material = material_index(spec, o.material);
    asset::add_to_scene(scene, std::move(model), o.transform, o.name, material);
}

// A scene without a camera is framed as it stands at time 0 (asset/framing.h); one without
// lights gets the default rig (asset/light_rig.h), placed for that camera.
void frame_and_light(render::AnimatedScene& out, const SceneSpec& spec) {
    scene::Scene& scene = out.scene;
    if (scene.objects.empty()) return;
    scene.animate(0.0f);
    const scene::BakedScene baked = scene::bake(scene);
    if (baked.mesh.positions.empty()) return;
    glm::vec3 lower = baked.mesh.positions[0], upper = lower;
    for (const glm::vec3& p : baked.mesh.positions) {
        lower = glm::min(lower, p);
        upper = glm::max(upper, p);
    }
    if (!spec.camera_given) {
        out.camera = render::CameraSpec{};
        // Framed for an aspect of at most 1, so that the scene fits any landscape --size too.
        out.camera.camera = asset::frame_box(lower, upper, std::min(1.0f, float(spec.size.x) / float(spec.size.y)));
        scene.camera = out.camera.camera;
    }
    if (!spec.lights_given) scene.lights = asset::default_light_rig(out.camera.camera, lower, upper);
}

void add_snake(scene::Scene& scene, const SceneSpec& spec, const ObjectSpec& o,
               const std::shared_ptr<const Ground>& ground) {
    const SnakeSpec snake = o.snake;
    // Without a heightfield the snake lies on the plane y = its transform's translation.y.
    const float plane = o.transform.translation.y;
    const geometry::GroundHeight height = ground ? geometry::GroundHeight([ground](float x, float z) { return ground->height(x, z); })
                                       : geometry::GroundHeight([plane](float, float) { return plane; });
    const uint32_t skin = material_index(spec, o.material);
    const uint32_t eye = snake.eye_material.empty() ? skin : material_index(spec, snake.eye_material);

    scene::Object body{o.name, std::make_shared<const Mesh>(geometry::snake_body(snake, geometry::snake_spine(snake, 0.0f, height))), skin, {}, {}};
    body.animate = [snake, height](scene::Object& self, float time) {
        self.geometry = std::make_shared<const Mesh>(geometry::snake_body(snake, geometry::snake_spine(snake, time, height)));
    };
    scene.objects.push_back(std::move(body));

    const auto place_head = [snake, height](scene::Object& self, float time) {
        const geometry::SnakeHead head = geometry::snake_head(snake, geometry::snake_spine(snake, time, height));
        self.transform.translation = head.centre;
        set_rotation(self.transform, head.orientation);
    };
    scene::Object head{o.name + " head", nullptr, skin, {}, place_head};
    const geometry::SnakeHead head0 = geometry::snake_head(snake, geometry::snake_spine(snake, 0.0f, height));
    head.geometry = std::make_shared<const Mesh>(geometry::tessellate(geometry::ellipsoid_surface(glm::vec3(0.0f), head0.radii), 32, 16));
    place_head(head, 0.0f);
    scene.objects.push_back(std::move(head));

    const auto eye_mesh = std::make_shared<const Mesh>(
        geometry::tessellate(geometry::sphere_surface(glm::vec3(0.0f), geometry::snake_eye_radius(snake)), 16, 8));
    for (float side : {-1.0f, 1.0f}) {
        const auto place_eye = [snake, height, side](scene::Object& self, float time) {
            const geometry::SnakeHead head = geometry::snake_head(snake, geometry::snake_spine(snake, time, height));
            self.transform.translation = head.centre + head.orientation * geometry::snake_eye_offset(head, side);
            set_rotation(self.transform, head.orientation);
        };
        scene::Object e{o.name + (side < 0 ? " left eye" : " right eye"), eye_mesh, eye, {}, place_eye};
        place_eye(e, 0.0f);
        scene.objects.push_back(std::move(e));
    }
}

// Object `o`'s geometry, transform and animation (snakes are add_snake's, model files
// add_model's); a heightfield's samples go to `grounds`, for the snakes lying on it.
scene::Object build_object(const SceneSpec& spec, const ObjectSpec& o,
                           std::map<std::string, std::shared_ptr<const Ground>>& grounds) {
    scene::Object object{o.name, nullptr, material_index(spec, o.material), o.transform, {}};
    const glm::ivec2 g = o.tessellation;
    switch (o.shape) {
        case ObjectSpec::Shape::sphere:
            object.geometry = std::make_shared<const Mesh>(geometry::tessellate(geometry::sphere_surface(o.centre, o.radius), g.x, g.y));
            break;
        case ObjectSpec::Shape::ellipsoid:
            object.geometry = std::make_shared<const Mesh>(geometry::tessellate(geometry::ellipsoid_surface(o.centre, o.radii), g.x, g.y));
            break;
        case ObjectSpec::Shape::torus:
            object.geometry = std::make_shared<const Mesh>(geometry::tessellate(geometry::torus_surface(o.major, o.minor), g.x, g.y));
            break;
        case ObjectSpec::Shape::flag: {
            const ObjectSpec flag = o;
            object.geometry = std::make_shared<const Mesh>(geometry::tessellate(
                geometry::flag_surface(o.flag_size.x, o.flag_size.y, o.flag_depth, o.flag_waves, 0.0f), g.x, g.y));
            if (o.wave_speed != 0.0f)
                object.animate = [flag](scene::Object& self, float time) {
                    self.geometry = std::make_shared<const Mesh>(geometry::tessellate(
                        geometry::flag_surface(flag.flag_size.x, flag.flag_size.y, flag.flag_depth, flag.flag_waves,
                                     flag.wave_speed * time),
                        flag.tessellation.x, flag.tessellation.y));
                };
            break;
        }
        case ObjectSpec::Shape::box:
            object.geometry = std::make_shared<const Mesh>(geometry::box_mesh(0.5f * o.box_size));
            break;
        case ObjectSpec::Shape::heightfield: {
            auto ground = std::make_shared<Ground>();
            ground->spec = o.heightfield;
            ground->offset = o.transform.translation;
            ground->heights = tp::generate_heightfield(o.heightfield.samples.x, o.heightfield.samples.y,
                                                       o.heightfield.relief);
            object.geometry = std::make_shared<const Mesh>(geometry::tessellate(
                geometry::heightfield_surface(ground->heights.values, ground->heights.width, ground->heights.height,
                                    o.heightfield.size, o.heightfield.height),
                ground->heights.width - 1, ground->heights.height - 1));
            object.transform = scene::Transform{};  // snakes sample the ground by translation only
            object.transform.translation = o.transform.translation;
            grounds[o.name] = ground;
            break;
        }
        case ObjectSpec::Shape::mesh: break;   // add_model's
        case ObjectSpec::Shape::snake: break;  // add_snake's
    }
    add_spin(object, o);
    return object;
}

}  // namespace

render::AnimatedScene build_scene(const SceneSpec& spec, std::vector<std::string>* warnings) {
    render::AnimatedScene out;
    scene::Scene& scene = out.scene;
    scene.lights = spec.lights;
    // A direction of any length: one whose square would overflow is scaled first
    // (direction.h), the shading then normalises it as any other.
    for (scene::Light& light : scene.lights)
        if (light.position.w == 0.0f) light.position = glm::vec4(*normalisable(glm::vec3(light.position)), 0.0f);
    scene.background = spec.background;
    scene.camera = spec.camera.camera;

    std::map<std::string, int32_t> texture_index;
    for (const TextureSpec& t : spec.textures) texture_index[t.name] = int32_t(texture_index.size());
    scene.textures = build_textures(spec);
    for (const MaterialSpec& m : spec.materials) {
        scene::Material material = m.material;
        if (!m.diffuse_texture.empty()) material.diffuse_texture = texture_index.at(m.diffuse_texture);
        if (!m.normal_texture.empty()) material.normal_texture = texture_index.at(m.normal_texture);
        scene.materials.push_back(material);
    }

    std::map<std::string, std::shared_ptr<const Ground>> grounds;
    for (size_t i = 0; i < spec.objects.size(); ++i) {
        const ObjectSpec& o = spec.objects[i];
        if (o.shape == ObjectSpec::Shape::snake) continue;  // after every ground exists
        const std::string pointer = "/objects/" + std::to_string(i);
        if (o.shape == ObjectSpec::Shape::mesh) {
            const size_t first = scene.objects.size();
            at_pointer(spec, pointer, [&] { add_model(scene, spec, o, pointer, warnings); });
            for (size_t k = first; k < scene.objects.size(); ++k) add_spin(scene.objects[k], o);
            continue;
        }
        scene.objects.push_back(at_pointer(spec, pointer, [&] { return build_object(spec, o, grounds); }));
    }
    for (size_t i = 0; i < spec.objects.size(); ++i) {
        const ObjectSpec& o = spec.objects[i];
        if (o.shape != ObjectSpec::Shape::snake) continue;
        at_pointer(spec, "/objects/" + std::to_string(i),
                   [&] { add_snake(scene, spec, o, o.snake.ground.empty() ? nullptr : grounds.at(o.snake.ground)); });
    }
    // The passes' own generators check their settings when the renderer builds them: check
    // them here, where the pass can be named.
    for (size_t i = 0; i < spec.passes.size(); ++i)
        if (spec.passes[i].kind == render::PassSpec::Kind::terrain)
            at_pointer(spec, "/passes/" + std::to_string(i), [&] { tp::TerrainField check(spec.passes[i].terrain); });

    out.camera = spec.camera;
    out.passes = spec.passes;
    at_pointer(spec, "/objects", [&] { scene.validate(); });
    if (!spec.camera_given || !spec.lights_given) frame_and_light(out, spec);
    return out;
}

}  // namespace tessera::scene_file
