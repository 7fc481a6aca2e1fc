// The scene over time, as one animation frame needs it: the renderable Scene (whose objects
// animate themselves), the camera's keyframes and orbit, and the ray-marched passes. A frame at
// time t is set_time(t, aspect), then the scene's bake (scene/scene.h).
#pragma once
#include <glm/glm.hpp>

#include <utility>
#include <vector>

#include "procedural/heightfield.h"
#include "raster/core/camera.h"
#include "raster/march/fog.h"
#include "raster/march/march_settings.h"
#include "raster/march/metaball_field.h"
#include "raster/march/surface_shading.h"
#include "raster/scene/scene.h"

namespace tessera::render {

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

// Ray-marched compute passes, run per tile after rasterization in list order.
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

struct AnimatedScene {
    scene::Scene scene;
    CameraSpec camera;
    std::vector<PassSpec> passes;

    // Runs every object's animate hook for `time` seconds and places the camera (its aspect
    // set to `aspect`).
    void set_time(float time, float aspect);
};

// A Scene built in code as an AnimatedScene (what FrameRenderer renders): its camera becomes
// the camera spec with no keys and no orbit, so set_time(t, aspect) keeps the pose, sets the
// aspect and runs the objects' own animate hooks, if any. No compute passes.
AnimatedScene still_scene(scene::Scene scene);

// The camera of `spec` at `time`: keyframes interpolated (Catmull-Rom in time), then the orbit.
Camera camera_at(const CameraSpec& spec, float time, float aspect);

// The lowest and highest fov the spline takes between keys[segment] and keys[segment + 1]
// (segment + 1 < keys.size()): Catmull-Rom overshoots the keys where they change steeply.
std::pair<float, float> fov_range(const std::vector<CameraKey>& keys, size_t segment);

}  // namespace tessera::render
