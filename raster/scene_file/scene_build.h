// From a SceneSpec to a renderable, animated Scene (scene/scene.h): textures generated or
// loaded once, geometry tessellated, and an animate hook on every object that moves (spins,
// waving flags, writhing snakes), so a frame at time t is scene.animate(t) then bake().
#pragma once
#include <string>
#include <vector>

#include "raster/render/animated_scene.h"
#include "raster/scene_file/scene_spec.h"

namespace tessera::scene_file {

// Throws SceneFileError "FILE: /json/pointer: ..." for a texture, OBJ or model file that
// cannot be read and for values the generators refuse, naming the texture, object or pass.
// Warnings (a model's texture that is missing, ...) are appended to `warnings` when given.
render::AnimatedScene build_scene(const SceneSpec& spec, std::vector<std::string>* warnings = nullptr);

}  // namespace tessera::scene_file
