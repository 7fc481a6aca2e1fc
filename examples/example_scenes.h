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

// The individual builders.
Scene flag_scene();
Scene toon_scene();
Scene bumpcube_scene();
Scene snakes_scene();

}  // namespace tessera::examples
