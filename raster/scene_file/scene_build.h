// From a SceneSpec to a renderable, animated Scene (scene/scene.h): textures generated or
// loaded once, geometry tessellated, and an animate hook on every object that moves (spins,
// waving flags, writhing snakes), so a frame at time t is scene.animate(t) then bake().
#pragma once
#include "raster/scene/scene.h"
#include "raster/scene_file/scene_spec.h"

namespace tessera {

struct AnimatedScene {
    SceneSpec spec;
    Scene scene;

    // Runs every object's animate hook for `time` seconds and places the camera (its aspect
    // set to `aspect`).
    void set_time(float time, float aspect);
};

// A Scene built in code as an AnimatedScene (what FrameRenderer renders): its camera becomes
// the camera spec with no keys and no orbit, so set_time(t, aspect) keeps the pose, sets the
// aspect and runs the objects' own animate hooks, if any. No compute passes.
AnimatedScene still_scene(Scene scene);

// Throws SceneFileError for a texture or OBJ file that cannot be read (naming the scene file
// and the texture or object), std::invalid_argument for values the generators reject.
AnimatedScene build_scene(SceneSpec spec);

// The camera of `spec` at `time`: keyframes interpolated (Catmull-Rom in time), then the orbit.
Camera camera_at(const CameraSpec& spec, float time, float aspect);

}  // namespace tessera
