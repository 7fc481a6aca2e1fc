// The built-in example scenes, built in code. Construction is kept apart from the `render`
// command so that a scene-file parser can produce the same Scene objects later.
//
//   flag      the seed's waving flag twice, Gouraud (left) and Phong (right), coarse enough
//             (16 x 6) for the difference to show; sky background
//   toon      NPR toon shading (two levels, black silhouettes) on a sphere, torus, ellipsoid
//   bumpcube  a rotating cube, reaction-diffusion colour texture and a normal map from a
//             procedural heightfield (seeds/004)
//   snakes    the "writhing snakes" homework (seeds/000): extruded Catmull-Rom bodies with
//             elliptical profiles, ellipsoid heads and eyes, reaction-diffusion skin with white
//             Blinn-Phong highlights, on procedural dune sand
// (obj_scene() frames any OBJ file the same way.)
#pragma once
#include <string>
#include <string_view>
#include <vector>

#include "raster/scene/scene.h"

namespace tessera::examples {

// Every name make_scene accepts.
std::vector<std::string> scene_names();

// Builds the named scene (animate(t) with any t gives its state at t seconds). Throws
// std::invalid_argument naming the valid scenes for an unknown name.
Scene make_scene(std::string_view name);

// A Wavefront OBJ mesh (raster/obj_loader.h) on its own: scaled and centred to fit a unit
// sphere, shaded with `model` (uv checker texture when the mesh has uv), lit by a key and a
// fill light, in front of the procedural sky. Throws tessera::Error for an unreadable file.
Scene obj_scene(const std::string& path, ShadingModel model);

// The individual builders.
Scene flag_scene();
Scene toon_scene();
Scene bumpcube_scene();
Scene snakes_scene();

}  // namespace tessera::examples
