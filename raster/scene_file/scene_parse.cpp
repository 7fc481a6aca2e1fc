#include "raster/scene_file/scene_parse.h"

#include <glm/gtc/constants.hpp>

#include <cmath>
#include <cstdint>
#include <stdexcept>

#include "procedural/rd_presets.h"
#include "raster/core/direction.h"
#include "raster/core/input_file.h"
#include "raster/io/camera_file.h"
#include "raster/io/obj_loader.h"
#include "raster/scene_file/json_reader.h"

namespace tessera::scene_file {
namespace {

using scene_file::JsonNode;

float radians_of(const JsonNode& node, const std::string& key, float fallback_rad) {
    // Angles are written in degrees in scene files (people think in degrees); stored radians.
    return glm::radians(node.number(key, glm::degrees(fallback_rad)));
}

float positive(const JsonNode& node, const std::string& key, float fallback) {
    const float v = node.number(key, fallback);
    if (!(v > 0.0f)) node.at(key).fail("must be positive");
    return v;
}

int at_least(const JsonNode& node, const std::string& key, int fallback, int low, int high) {
    const int v = node.integer(key, fallback);
    if (v < low || v > high)
        node.at(key).fail("must lie in " + std::to_string(low) + ".." + std::to_string(high));
    return v;
}

// Scene values are read as floats, and the renderer squares and multiplies them: a value whose
// square or product would overflow is refused here, naming it, rather than rendered as Inf
// or nothing. Positions lie within 1e18 of the origin, as OBJ vertices do
// (io::kMaxObjCoordinate), so squared distances stay finite; radiances within 1e12 and
// reflectances within 1e6, so that their products over any number of lights stay far
// inside float (3.4e38).
constexpr float kMaxCoordinate = io::kMaxObjCoordinate;
constexpr float kMaxRadiance = 1e12f;
constexpr float kMaxReflectance = 1e6f;

glm::vec3 position(const JsonNode& node, const std::string& key, glm::vec3 fallback) {
    const glm::vec3 v = node.vec3(key, fallback);
    for (int i = 0; i < 3; ++i)
        if (std::fabs(v[i]) > kMaxCoordinate) node.at(key).fail("coordinates must lie within +-1e18");
    return v;
}

// A colour or radiance: components in [0, high].
glm::vec3 colour(const JsonNode& node, const std::string& key, glm::vec3 fallback, float high) {
    const glm::vec3 v = node.vec3(key, fallback);
    for (int i = 0; i < 3; ++i)
        if (!(v[i] >= 0.0f && v[i] <= high))
            node.at(key).fail(high == kMaxRadiance ? "components must lie in [0, 1e12]" : "components must lie in [0, 1e6]");
    return v;
}

// A direction of any length but zero, kept as given unless its square would overflow or
// underflow (then scaled: core/direction.h), so the renderer can normalise it.
template <glm::length_t N>
glm::vec<N, float> direction(const JsonNode& node, const std::string& key, glm::vec<N, float> fallback) {
    glm::vec<N, float> v = fallback;
    if (const auto n = node.find(key)) {
        if constexpr (N == 2) v = n->as_vec2();
        else v = n->as_vec3();
    }
    const auto scaled = normalisable(v);
    if (!scaled) node.at(key).fail("must not be zero");
    return *scaled;
}

// A camera that cannot form a view (eye on the lookat point, up along the view, ...), with
// `node` naming where it was given.
void check_pose(const JsonNode& node, const Camera& camera) {
    try {
        io::validate_camera(camera);
    } catch (const std::invalid_argument& e) {
        node.fail(e.what());
    }
}

glm::ivec2 grid_of(const JsonNode& node, const std::string& key, glm::ivec2 fallback, int high) {
    const auto n = node.find(key);
    if (!n) return fallback;
    if (!n->is_array() || n->raw().size() != 2) n->fail("expected an array of 2 integers");
    const auto e = n->elements();
    const glm::ivec2 v{e[0].as_integer(), e[1].as_integer()};
    if (v.x < 1 || v.y < 1 || v.x > high || v.y > high)
        n->fail("each count must lie in 1.." + std::to_string(high));
    return v;
}

Camera parse_camera_pose(const JsonNode& n, Camera c) {
    c.eye = position(n, "eye", c.eye);
    c.lookat = position(n, "lookat", c.lookat);
    c.up = direction(n, "up", c.up);
    c.fovy_deg = n.number("fov", c.fovy_deg);
    if (!(c.fovy_deg > 0.0f && c.fovy_deg < 179.0f)) n.at("fov").fail("must lie in (0, 179) degrees");
    c.near = n.number("near", c.near);
    c.far = n.number("far", c.far);
    if (n.has("near") || n.has("far"))
        if (!(c.near > 0.0f && c.far > c.near)) n.fail("needs 0 < near < far");
    return c;
}

// Each keyframe's pose is checked as the static one is, and the fov spline between keys
// over its whole length: Catmull-Rom overshoots (keys 10, 170, 170, 10 reach 190 between the
// two 170s), which would turn the image upside down at the frames in between.
void check_keyframes(const JsonNode& keys, const render::CameraSpec& spec) {
    const auto elements = keys.elements();
    for (size_t i = 0; i < spec.keys.size(); ++i) {
        Camera pose = spec.camera;
        pose.eye = spec.keys[i].eye, pose.lookat = spec.keys[i].lookat, pose.fovy_deg = spec.keys[i].fovy_deg;
        check_pose(elements[i], pose);
    }
    for (size_t i = 0; i + 1 < spec.keys.size(); ++i) {
        const auto [low, high] = render::fov_range(spec.keys, i);
        if (!(low > 0.0f && high < 179.0f))
            keys.fail("the fov spline between keyframes " + std::to_string(i) + " and " + std::to_string(i + 1) +
                      " reaches " + std::to_string(std::lround(low > 0.0f ? high : low)) +
                      " degrees, outside (0, 179) (Catmull-Rom overshoots so steep a change; add keyframes or "
                      "soften it)");
    }
}

render::CameraSpec parse_camera(const JsonNode& n) {
    n.expect_object();
    render::CameraSpec spec;
    spec.camera = parse_camera_pose(n, spec.camera);
    spec.orbit = glm::radians(n.number("orbit", 0.0f));  // degrees per second
    if (const auto keys = n.find("keyframes")) {
        for (const JsonNode& k : keys->elements()) {
            k.expect_object();
            render::CameraKey key;
            key.time = k.at("time").as_number();
            key.eye = position(k, "eye", spec.camera.eye);
            key.lookat = position(k, "lookat", spec.camera.lookat);
            key.fovy_deg = k.number("fov", spec.camera.fovy_deg);
            if (!(key.fovy_deg > 0.0f && key.fovy_deg < 179.0f)) k.at("fov").fail("must lie in (0, 179) degrees");
            if (!spec.keys.empty() && !(key.time > spec.keys.back().time))
                k.at("time").fail("keyframe times must increase");
            spec.keys.push_back(key);
            k.finish();
        }
        check_keyframes(*keys, spec);
    } else {
        check_pose(n, spec.camera);
    }
    n.finish();
    return spec;
}

scene::Background parse_background(const JsonNode& n) {
    n.expect_object();
    scene::Background b;
    const std::string type = n.string("type", "colour");
    if (type == "colour") {
        b.kind = scene::Background::Kind::colour;
        b.colour = colour(n, "colour", b.colour, kMaxRadiance);
    } else if (type == "sky") {
        b.kind = scene::Background::Kind::sky;
        b.sky.zenith = colour(n, "zenith", b.sky.zenith, kMaxRadiance);
        b.sky.horizon = colour(n, "horizon", b.sky.horizon, kMaxRadiance);
        b.sky.ground = colour(n, "ground", b.sky.ground, kMaxRadiance);
        b.sky.sun_direction = direction(n, "sun_direction", b.sky.sun_direction);
        b.sky.sun = colour(n, "sun", b.sky.sun, kMaxRadiance);
    } else {
        n.at("type").fail("unknown background '" + type + "' (expected colour or sky)");
    }
    n.finish();
    return b;
}

// A light's "shadow_map": {"size", "cascades", "split_blend", "pcf", "normal_offset",
// "depth_bias"}, each optional (core/shadow_map_settings.h).
ShadowMapSettings parse_shadow_map(const JsonNode& n) {
    n.expect_object();
    ShadowMapSettings s;
    s.resolution = n.integer("size", s.resolution);
    s.cascades = n.integer("cascades", s.cascades);
    s.split_blend = n.number("split_blend", s.split_blend);
    s.pcf_radius = n.integer("pcf", s.pcf_radius);
    s.normal_offset = n.number("normal_offset", s.normal_offset);
    s.depth_bias = n.number("depth_bias", s.depth_bias);
    n.finish();
    try {
        check_shadow_map_settings(s);
    } catch (const std::invalid_argument& e) {
        n.fail(e.what());
    }
    return s;
}

scene::Light parse_light(const JsonNode& n) {
    n.expect_object();
    scene::Light light;
    if (n.has("position") == n.has("direction"))
        n.fail("a light needs exactly one of 'position' (point light) or 'direction' (towards a distant light)");
    if (n.has("position")) light.position = glm::vec4(position(n, "position", {}), 1.0f);
    else light.position = glm::vec4(direction(n, "direction", glm::vec3(0.0f)), 0.0f);
    light.La = colour(n, "La", light.La, kMaxRadiance);
    light.Le = colour(n, "Le", light.Le, kMaxRadiance);
    if (const auto map = n.find("shadow_map")) light.shadow_map = parse_shadow_map(*map);
    n.finish();
    return light;
}

procedural::Relief parse_relief(const JsonNode& n, const std::string& key) {
    const std::string r = n.string(key, "fbm");
    if (r == "fbm") return procedural::Relief::fbm;
    if (r == "ridged") return procedural::Relief::ridged;
    if (r == "warped") return procedural::Relief::warped;
    if (r == "dunes") return procedural::Relief::dunes;
    n.at(key).fail("unknown relief '" + r + "' (expected fbm, ridged, warped or dunes)");
}

procedural::Dunes parse_dunes(const JsonNode& n, procedural::Dunes d) {
    d.wind = glm::normalize(direction(n, "wind", d.wind));
    d.wavelength = positive(n, "wavelength", d.wavelength);
    d.lee_fraction = n.number("lee_fraction", d.lee_fraction);
    d.sinuosity = n.number("sinuosity", d.sinuosity);
    d.ripple_wavelength = positive(n, "ripple_wavelength", d.ripple_wavelength);
    d.ripple_amplitude = n.number("ripple_amplitude", d.ripple_amplitude);
    return d;
}

// The heightfield generator's settings ("relief", "octaves", "cells", "seed", dune keys).
procedural::HeightfieldParams parse_heightfield_params(const JsonNode& n, procedural::HeightfieldParams p) {
    p.relief = parse_relief(n, "relief");
    p.fractal.octaves = at_least(n, "octaves", p.fractal.octaves, 1, 24);
    p.fractal.gain = n.number("gain", p.fractal.gain);
    if (!(p.fractal.gain > 0.0f && p.fractal.gain < 1.0f)) n.at("gain").fail("must lie in (0, 1)");
    p.fractal.seed = uint32_t(at_least(n, "seed", int(p.fractal.seed), 0, 1 << 30));
    p.cells = at_least(n, "cells", p.cells, 1, 4096);
    p.warp = n.number("warp", p.warp);
    p.dunes = parse_dunes(n, p.dunes);
    p.dunes.seed = p.fractal.seed;
    return p;
}

TextureSpec parse_texture(const std::string& name, const JsonNode& n) {
    n.expect_object();
    TextureSpec t;
    t.name = name;
    const std::string type = n.at("type").as_string();
    if (type == "file") {
        t.kind = TextureSpec::Kind::file;
        t.file = n.at("file").as_string();
        const std::string enc = n.string("encoding", "srgb");
        if (enc == "srgb") t.encoding = texture::TexelEncoding::srgb;
        else if (enc == "linear") t.encoding = texture::TexelEncoding::linear;
        else n.at("encoding").fail("expected srgb or linear");
    } else if (type == "reaction_diffusion") {
        t.kind = TextureSpec::Kind::reaction_diffusion;
        t.preset = n.string("preset", t.preset);
        if (!procedural::find_rd_preset(t.preset))
            n.at("preset").fail("unknown preset '" + t.preset + "' (expected " + procedural::rd_preset_names() + ")");
        t.size = at_least(n, "size", t.size, 8, 4096);
        t.steps = at_least(n, "steps", t.steps, 0, 1000000);
        t.grow_per_frame = at_least(n, "grow_per_frame", t.grow_per_frame, 0, 100000);
        t.seed = uint32_t(at_least(n, "seed", int(t.seed), 0, 1 << 30));
        t.anisotropy = n.number("anisotropy", t.anisotropy);
        if (!(t.anisotropy >= -1.0f && t.anisotropy <= 1.0f)) n.at("anisotropy").fail("must lie in [-1, 1]");
        if (const auto ramp = n.find("ramp")) {
            for (const JsonNode& stop : ramp->elements()) {
                stop.expect_object();
                const float at = stop.at("at").as_number();
                const glm::vec3 c = stop.at("colour").as_vec3();
                if (!t.ramp.empty() && !(at > t.ramp.back().position))
                    stop.at("at").fail("ramp positions must increase");
                t.ramp.push_back({at, {c.x, c.y, c.z}});
                stop.finish();
            }
            if (t.ramp.size() < 2) ramp->fail("a ramp needs at least 2 stops");
        }
    } else if (type == "relief_normals") {
        t.kind = TextureSpec::Kind::relief_normals;
        t.size = at_least(n, "size", t.size, 8, 4096);
        t.relief = parse_heightfield_params(n, t.relief);
        t.strength = positive(n, "strength", t.strength);
    } else {
        n.at("type").fail("unknown texture type '" + type + "' (expected file, reaction_diffusion or relief_normals)");
    }
    n.finish();
    return t;
}

MaterialSpec parse_material(const std::string& name, const JsonNode& n) {
    n.expect_object();
    MaterialSpec m;
    m.name = name;
    // Each parameter's JSON type is checked here (so the error names its path); the values'
    // meaning and whether the model uses them is set_material_parameters' business.
    std::vector<scene::MaterialParameter> params;
    for (const char* key : {"ka", "kd", "ks"})
        if (n.has(key)) {
            const glm::vec3 c = colour(n, key, glm::vec3(0.0f), kMaxReflectance);
            params.push_back({key, {c.x, c.y, c.z}, {}});
        }
    for (const char* key : {"shine", "opacity"})
        if (const auto v = n.find(key)) params.push_back({key, {v->as_number()}, {}});
    if (const auto v = n.find("uv_scale")) {
        const glm::vec2 s = v->as_vec2();
        params.push_back({"uv_scale", {s.x, s.y}, {}});
    }
    for (const char* key : {"model", "filter", "wrap"})
        if (const auto v = n.find(key)) params.push_back({key, {}, v->as_string()});
    m.diffuse_texture = n.string("diffuse_texture", "");
    m.normal_texture = n.string("normal_texture", "");
    // A diffuse texture is an albedo map: it colours the ambient term as well as the diffuse
    // one, or faces that only the ambient light reaches go flat.
    m.material.textured_ambient = n.boolean("ambient_texture", true);
    if (n.find("ambient_texture") && m.diffuse_texture.empty())
        n.warn("'ambient_texture' without a 'diffuse_texture' has no effect");
    try {
        for (const std::string& w : scene::set_material_parameters(m.material, params)) n.warn(w);
    } catch (const std::invalid_argument& e) {
        n.fail(e.what());
    }
    if (!m.normal_texture.empty() && (m.material.model == scene::ShadingModel::gouraud || m.material.model == scene::ShadingModel::flat))
        n.warn("'normal_texture' is not used by the " + std::string(to_string(m.material.model)) + " model; ignored");
    n.finish();
    return m;
}

scene::Transform parse_transform(const JsonNode& n) {
    n.expect_object();
    scene::Transform t;
    if (const auto s = n.find("scale")) {
        if (s->raw().is_number()) t.scale = glm::vec3(s->as_number());
        else t.scale = s->as_vec3();
        if (t.scale.x == 0.0f || t.scale.y == 0.0f || t.scale.z == 0.0f) s->fail("scale must not be zero");
    }
    t.angle = radians_of(n, "angle", 0.0f);
    // Any length: scene::Transform normalises it safely (core/direction.h).
    t.axis = t.angle != 0.0f ? direction(n, "axis", t.axis) : n.vec3("axis", t.axis);
    t.translation = n.vec3("translate", t.translation);
    n.finish();
    return t;
}

SnakeSpec parse_snake(const JsonNode& n, SnakeSpec s) {
    s.centre = n.vec2("centre", s.centre);
    s.path_radii = n.vec2("path_radii", s.path_radii);
    if (!(s.path_radii.x > 0.0f && s.path_radii.y > 0.0f)) n.at("path_radii").fail("must be positive");
    s.path_angle = radians_of(n, "path_angle", s.path_angle);
    s.phase = radians_of(n, "phase", s.phase);
    s.speed = n.number("speed", s.speed);
    s.length = positive(n, "length", s.length);
    s.width = positive(n, "width", s.width);
    s.height_ratio = positive(n, "height_ratio", s.height_ratio);
    s.control_points = at_least(n, "control_points", s.control_points, 4, 64);
    s.wiggle = n.number("wiggle", s.wiggle);
    s.wiggle_period = positive(n, "wiggle_period", s.wiggle_period);
    s.period_spread = n.number("period_spread", s.period_spread);
    s.wave_phase = n.number("wave_phase", s.wave_phase);
    s.tessellation = grid_of(n, "tessellation", s.tessellation, 4096);
    if (s.tessellation.y < 3) n.at("tessellation").fail("needs at least 3 segments around the body");
    s.ground = n.string("ground", s.ground);
    s.eye_material = n.string("eye_material", s.eye_material);
    return s;
}

ObjectSpec parse_object(const JsonNode& n, size_t index) {
    n.expect_object();
    ObjectSpec o;
    o.name = n.string("name", "object " + std::to_string(index));
    // A mesh brings its own materials; "material" overrides them.
    if (n.string("type", "") != "mesh" || n.find("material")) o.material = n.at("material").as_string();
    if (const auto t = n.find("transform")) o.transform = parse_transform(*t);
    if (const auto spin = n.find("spin")) {
        spin->expect_object();
        o.spin_axis = direction(*spin, "axis", o.spin_axis);
        o.spin = glm::radians(spin->number("speed", 0.0f));  // degrees per second
        spin->finish();
    }
    const std::string type = n.at("type").as_string();
    o.tessellation = grid_of(n, "tessellation", o.tessellation, 4096);
    if (type == "sphere") {
        o.shape = ObjectSpec::Shape::sphere;
        o.centre = n.vec3("centre", o.centre);
        o.radius = positive(n, "radius", o.radius);
    } else if (type == "ellipsoid") {
        o.shape = ObjectSpec::Shape::ellipsoid;
        o.centre = n.vec3("centre", o.centre);
        o.radii = n.vec3("radii", o.radii);
        if (!(o.radii.x > 0.0f && o.radii.y > 0.0f && o.radii.z > 0.0f)) n.at("radii").fail("must be positive");
    } else if (type == "torus") {
        o.shape = ObjectSpec::Shape::torus;
        o.major = positive(n, "major", o.major);
        o.minor = positive(n, "minor", o.minor);
        if (!(o.minor < o.major)) n.at(n.has("minor") ? "minor" : "major").fail("a torus needs minor < major");
    } else if (type == "flag") {
        o.shape = ObjectSpec::Shape::flag;
        o.flag_size = n.vec2("size", o.flag_size);
        if (!(o.flag_size.x > 0.0f && o.flag_size.y > 0.0f)) n.at("size").fail("must be positive");
        o.flag_depth = n.number("depth", o.flag_depth);
        o.flag_waves = n.number("waves", o.flag_waves);
        o.wave_speed = n.number("wave_speed", o.wave_speed);
    } else if (type == "box") {
        o.shape = ObjectSpec::Shape::box;
        o.box_size = n.vec3("size", o.box_size);
        if (!(o.box_size.x > 0.0f && o.box_size.y > 0.0f && o.box_size.z > 0.0f)) n.at("size").fail("must be positive");
    } else if (type == "heightfield") {
        o.shape = ObjectSpec::Shape::heightfield;
        HeightfieldSpec& h = o.heightfield;
        h.relief = parse_heightfield_params(n, h.relief);
        h.samples = grid_of(n, "samples", h.samples, 8192);
        if (h.samples.x < 2 || h.samples.y < 2) n.at("samples").fail("needs at least 2 x 2 samples");
        h.size = n.vec2("size", h.size);
        if (!(h.size.x > 0.0f && h.size.y > 0.0f)) n.at("size").fail("must be positive");
        h.height = n.number("height", h.height);
    } else if (type == "snake") {
        o.shape = ObjectSpec::Shape::snake;
        o.snake = parse_snake(n, o.snake);
    } else if (type == "mesh") {
        o.shape = ObjectSpec::Shape::mesh;
        o.file = n.at("file").as_string();
    } else {
        n.at("type").fail("unknown object type '" + type +
                          "' (expected sphere, ellipsoid, torus, flag, box, heightfield, snake or mesh)");
    }
    n.finish();
    return o;
}

march::SurfaceMaterial parse_surface_material(const JsonNode& n, march::SurfaceMaterial m) {
    n.expect_object();
    m.diffuse = n.vec3("kd", m.diffuse);
    m.specular = n.vec3("ks", m.specular);
    m.shininess = n.number("shine", m.shininess);
    m.ambient = n.vec3("ka", m.ambient);
    m.reflectivity = n.number("reflectivity", m.reflectivity);
    if (!(m.reflectivity >= 0.0f && m.reflectivity <= 1.0f)) n.at("reflectivity").fail("must lie in [0, 1]");
    n.finish();
    return m;
}

march::MarchSettings parse_march(const JsonNode& n, march::MarchSettings s) {
    const std::string strategy = n.string("strategy", "uniform");
    if (strategy == "uniform") s.strategy = march::StepStrategy::uniform;
    else if (strategy == "geometric") s.strategy = march::StepStrategy::geometric;
    else n.at("strategy").fail("expected uniform or geometric");
    s.steps = at_least(n, "steps", s.steps, 1, 4096);
    if (n.has("max_step")) s.max_step = positive(n, "max_step", 1.0f);
    s.growth = n.number("growth", s.growth);
    s.tolerance = positive(n, "tolerance", s.tolerance);
    try {
        s.validate();
    } catch (const std::invalid_argument& e) {
        n.fail(e.what());
    }
    return s;
}

render::PassSpec parse_pass(const JsonNode& n) {
    n.expect_object();
    render::PassSpec p;
    const std::string type = n.at("type").as_string();
    if (type == "terrain") {
        p.kind = render::PassSpec::Kind::terrain;
        procedural::TerrainParams& t = p.terrain;
        t.relief = parse_relief(n, "relief");
        t.fractal.octaves = at_least(n, "octaves", t.fractal.octaves, 1, 24);
        t.fractal.gain = n.number("gain", t.fractal.gain);
        if (!(t.fractal.gain > 0.0f && t.fractal.gain < 1.0f)) n.at("gain").fail("must lie in (0, 1)");
        t.fractal.seed = uint32_t(at_least(n, "seed", 0, 0, 1 << 30));
        t.frequency = positive(n, "frequency", t.frequency);
        t.amplitude = positive(n, "amplitude", t.amplitude);
        t.base = n.number("base", t.base);
        t.warp = n.number("warp", t.warp);
        t.dunes = parse_dunes(n, t.dunes);
        p.settings = parse_march(n, p.settings);
        if (const auto m = n.find("material")) p.material = parse_surface_material(*m, p.material);
    } else if (type == "metaballs") {
        p.kind = render::PassSpec::Kind::metaballs;
        p.count = at_least(n, "count", p.count, 1, 4096);
        p.ball_radius = positive(n, "radius", p.ball_radius);
        p.orbit_scale = positive(n, "orbit_scale", p.orbit_scale);
        p.offset = n.vec3("offset", p.offset);
        const std::string kernel = n.string("kernel", "wyvill");
        if (kernel == "wyvill") p.style.kernel = march::MetaballKernel::wyvill;
        else if (kernel == "perlin") p.style.kernel = march::MetaballKernel::perlin;
        else if (kernel == "blinn") p.style.kernel = march::MetaballKernel::blinn;
        else n.at("kernel").fail("expected wyvill, perlin or blinn");
        p.style.threshold = positive(n, "threshold", p.style.threshold);
        p.settings = parse_march(n, p.settings);
        if (const auto m = n.find("material")) p.material = parse_surface_material(*m, p.material);
    } else if (type == "fog") {
        p.kind = render::PassSpec::Kind::fog;
        p.fog.density = n.vec3("density", p.fog.density);
        p.fog.colour = n.vec3("colour", p.fog.colour);
        p.fog.falloff = n.number("falloff", p.fog.falloff);
        p.fog.base_height = n.number("base_height", p.fog.base_height);
        try {
            p.fog.validate();
        } catch (const std::invalid_argument& e) {
            n.fail(e.what());
        }
    } else {
        n.at("type").fail("unknown pass type '" + type + "' (expected terrain, metaballs or fog)");
    }
    n.finish();
    return p;
}

template <class Spec>
void check_unique(const std::vector<Spec>& specs, const JsonNode& n, const char* what) {
    for (size_t i = 0; i < specs.size(); ++i)
        for (size_t j = 0; j < i; ++j)
            if (specs[i].name == specs[j].name) n.fail(std::string("two ") + what + " are named '" + specs[i].name + "'");
}

template <class Spec>
bool named(const std::vector<Spec>& specs, const std::string& name) {
    for (const Spec& s : specs)
        if (s.name == name) return true;
    return false;
}

// Cross references: every name used must exist.
void check_references(const SceneSpec& s, const JsonNode& root) {
    const auto objects = root.at("objects").elements();
    for (size_t i = 0; i < s.materials.size(); ++i) {
        const MaterialSpec& m = s.materials[i];
        for (const std::string* t : {&m.diffuse_texture, &m.normal_texture})
            if (!t->empty() && !named(s.textures, *t))
                root.at("materials").at(m.name).fail("texture '" + *t + "' is not defined in /textures");
    }
    for (size_t i = 0; i < s.objects.size(); ++i) {
        const ObjectSpec& o = s.objects[i];
        if (o.shape == ObjectSpec::Shape::mesh && o.material.empty()) continue;  // its own materials
        if (!named(s.materials, o.material))
            objects[i].at("material").fail("material '" + o.material + "' is not defined in /materials");
        if (o.shape != ObjectSpec::Shape::snake) continue;
        if (!o.snake.eye_material.empty() && !named(s.materials, o.snake.eye_material))
            objects[i].at("eye_material").fail("material '" + o.snake.eye_material + "' is not defined in /materials");
        if (!o.snake.ground.empty()) {
            bool found = false;
            for (const ObjectSpec& g : s.objects)
                found |= g.name == o.snake.ground && g.shape == ObjectSpec::Shape::heightfield;
            if (!found) objects[i].at("ground").fail("no heightfield object is named '" + o.snake.ground + "'");
        }
    }
}

// Why `text` is not JSON, as nlohmann words it without its "[json.exception.*] " prefix:
// "parse error at line L, column C: ...", or "number overflow parsing '1e999'" for a number
// beyond double (nlohmann's out_of_range 406). The handler stops at the first error.
std::string json_error(const std::string& text) {
    struct FirstError : nlohmann::json_sax<nlohmann::ordered_json> {
        std::string message = "not valid JSON";
        bool null() override { return true; }
        bool boolean(bool) override { return true; }
        bool number_integer(number_integer_t) override { return true; }
        bool number_unsigned(number_unsigned_t) override { return true; }
        bool number_float(number_float_t, const string_t&) override { return true; }
        bool string(string_t&) override { return true; }
        bool binary(binary_t&) override { return true; }
        bool start_object(std::size_t) override { return true; }
        bool key(string_t&) override { return true; }
        bool end_object() override { return true; }
        bool start_array(std::size_t) override { return true; }
        bool end_array() override { return true; }
        bool parse_error(std::size_t, const std::string&,
                         const nlohmann::detail::exception& error) override {
            message = error.what();
            const size_t bracket = message.find("] ");
            if (message.rfind("[json.exception.", 0) == 0 && bracket != std::string::npos)
                message = message.substr(bracket + 2);
            return false;
        }
    } handler;
    nlohmann::ordered_json::sax_parse(text, &handler);
    return handler.message;
}

}  // namespace

SceneSpec parse_scene(const std::string& json_text, const std::string& label,
                      std::vector<std::string>& warnings) {
    // Parsed with exceptions off: malformed input is a return value, not a throw through
    // nlohmann's parser (a clang build once terminated there on "1e320" followed by a syntax
    // error, issue 10); the message is recovered by a second, error-recording pass.
    const nlohmann::ordered_json doc = nlohmann::ordered_json::parse(json_text, nullptr, false);
    if (doc.is_discarded()) throw SceneFileError(label + ": malformed JSON: " + json_error(json_text));
    for (const std::string& pointer : repeated_keys(json_text))
        warnings.push_back(one_line_diagnostic(label + ": " + pointer + ": the key is given twice; the last value is used"));
    const scene_file::Diagnostics diagnostics{label, &warnings};
    const JsonNode root(doc, "", diagnostics);
    root.expect_object();

    SceneSpec s;
    s.description = root.string("description", "");
    if (const auto c = root.find("camera")) {
        s.camera = parse_camera(*c);
        s.camera_given = true;
    }
    if (const auto b = root.find("background")) s.background = parse_background(*b);
    if (const auto lights = root.find("lights")) {
        for (const JsonNode& l : lights->elements()) s.lights.push_back(parse_light(l));
        s.lights_given = true;
    }
    if (const auto textures = root.find("textures"))
        for (const auto& [name, t] : textures->members()) s.textures.push_back(parse_texture(name, t));
    if (const auto materials = root.find("materials"))
        for (const auto& [name, m] : materials->members()) s.materials.push_back(parse_material(name, m));
    const auto objects = root.at("objects").elements();
    for (size_t i = 0; i < objects.size(); ++i) s.objects.push_back(parse_object(objects[i], i));
    if (const auto passes = root.find("passes"))
        for (const JsonNode& p : passes->elements()) s.passes.push_back(parse_pass(p));
    if (const auto a = root.find("animation")) {
        a->expect_object();
        s.animation.fps = positive(*a, "fps", s.animation.fps);
        if (const auto f = a->find("frames")) {
            const auto e = f->elements();
            if (e.size() != 2) f->fail("expected [first, last]");
            s.animation.first = e[0].as_integer();
            s.animation.last = e[1].as_integer();
            if (s.animation.first < 0 || s.animation.last < s.animation.first) f->fail("needs 0 <= first <= last");
        }
        a->finish();
    }
    if (const auto r = root.find("render")) {
        r->expect_object();
        s.size = grid_of(*r, "size", s.size, 1 << 16);
        s.shadows = r->string("shadows", s.shadows);
        if (s.shadows != "none" && s.shadows != "map" && s.shadows != "rays")
            r->at("shadows").fail("expected none, map or rays");
        s.samples = r->integer("samples", s.samples);
        if (s.samples != 1 && s.samples != 4 && s.samples != 8 && s.samples != 16)
            r->at("samples").fail("expected 1, 4, 8 or 16 samples per pixel");
        r->finish();
    }
    check_unique(s.textures, root, "textures");
    check_unique(s.materials, root, "materials");
    check_unique(s.objects, root, "objects");
    check_references(s, root);
    root.finish();
    return s;
}

SceneSpec load_scene_file(const std::filesystem::path& path, std::vector<std::string>& warnings) {
    // A device, FIFO or directory is refused at once; so is a file too large to be a scene
    // (its meshes and textures are files of their own), before it is read.
    constexpr uint64_t kMaxSceneBytes = uint64_t(64) << 20;
    std::string text;
    try {
        InputFile file(path, "scene file");
        if (file.size() > kMaxSceneBytes)
            throw SceneFileError("cannot read scene file '" + path.string() + "': it holds " +
                                 std::to_string(file.size() >> 20) + " MiB, a scene file at most 64 MiB");
        text = file.read_rest();
    } catch (const SceneFileError&) {
        throw;
    } catch (const Error& e) {
        throw SceneFileError(e.what());
    }
    SceneSpec spec = parse_scene(text, path.string(), warnings);
    spec.file = path;
    return spec;
}

}  // namespace tessera::scene_file
