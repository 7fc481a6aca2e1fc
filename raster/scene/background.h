// What a pixel shows where no surface covers it: a constant colour, a procedural sky, or a
// cube map made of six images. This is the description; shade/background_radiance.h
// evaluates it along a ray.
#pragma once
#include <glm/glm.hpp>

#include <array>
#include <string>
#include <memory>

#include "raster/texture/texture.h"

namespace tessera::scene {

// Procedural sky: a gradient from `horizon` to `zenith` above the horizon, fading to `ground`
// below it, smooth (no kink) across the horizon, and a sun disc with a soft glow around
// `sun_direction`.
struct Sky {
    glm::vec3 zenith{0.10f, 0.28f, 0.65f};
    glm::vec3 horizon{0.70f, 0.80f, 0.92f};
    glm::vec3 ground{0.25f, 0.22f, 0.20f};
    glm::vec3 sun_direction{0.4f, 0.6f, 0.3f};  // towards the sun; need not be unit length
    glm::vec3 sun{20.0f, 18.0f, 15.0f};         // radiance inside the disc
};

// A cube map, faces in OpenGL order +x, -x, +y, -y, +z, -z, looked up as the OpenGL 4.6
// specification (section 8.13, table 8.19) selects face and (s, t); each face image's top row
// is t = 0 there, so the lookup reads v = 1 - t of the bottom-up Texture.
struct CubeMap {
    std::array<std::shared_ptr<const texture::Texture>, 6> faces;
};

// Reads six colour images named by `pattern` with "{face}" replaced by px, nx, py, ny, pz, nz
// ("sky/{face}.png" -> sky/px.png ...). Throws std::invalid_argument for a pattern without
// "{face}" and tessera::Error naming a missing or unreadable face.
CubeMap load_cube_map(const std::string& pattern);

struct Background {
    enum class Kind { colour, sky, cube_map } kind = Kind::colour;
    glm::vec3 colour{0.0f};
    Sky sky;
    CubeMap cube;
};

}  // namespace tessera::scene
