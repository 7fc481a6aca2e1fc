// The environment: radiance arriving from infinitely far away in a direction (seeds/003,
// "environment as background": a full-screen pass looks up a cube map with the per-pixel ray
// direction). It is the background where nothing was hit and what mirror-like marched
// surfaces reflect.
//
// Two sources:
// - a cube map from six images in OpenGL's order +x, -x, +y, -y, +z, -z, addressed with the
//   OpenGL face-selection rule (GL 4.6 core, section 8.13 "Cube Map Texture Selection") and
//   filtered bilinearly within a face;
// - a procedural sky where no images exist: a horizon-to-zenith gradient, a ground colour
//   below the horizon and a sun lobe pow(max(d . sun, 0), sharpness).
// Colours are linear radiance.
#pragma once
#include <glm/glm.hpp>

#include <array>
#include <filesystem>
#include <vector>

#include "raster/image_io.h"

namespace tessera::march {

struct Sky {
    glm::vec3 zenith{0.18f, 0.36f, 0.78f};
    glm::vec3 horizon{0.72f, 0.80f, 0.90f};
    glm::vec3 ground{0.28f, 0.25f, 0.22f};
    glm::vec3 sun_direction{0.4f, 0.55f, -0.73f};  // towards the sun; normalised on use
    glm::vec3 sun_colour{6.0f, 5.4f, 4.6f};
    float sun_sharpness = 900.0f;  // the lobe's exponent; larger is a smaller sun
};

class Environment {
public:
    // Throws std::invalid_argument for non-finite colours, a zero sun direction or a
    // non-positive sharpness.
    static Environment procedural(const Sky& sky);

    // Six square faces of one size with at least three channels, already linear.
    // Throws std::invalid_argument naming the face that does not fit.
    static Environment cube_map(std::array<FloatImage, 6> faces);

    // Reads six image files (+x, -x, +y, -y, +z, -z) through OpenImageIO. 8- and 16-bit
    // files are sRGB-encoded and are decoded to linear; float formats (EXR, HDR) are used as
    // stored. Throws tessera::Error for files that cannot be read, std::invalid_argument for
    // faces that do not fit together.
    static Environment load_cube_map(const std::array<std::filesystem::path, 6>& paths);

    // Radiance from direction `d` (any length > 0).
    glm::vec3 radiance(glm::vec3 d) const;

    bool is_cube_map() const { return !faces_[0].pixels.empty(); }

private:
    glm::vec3 sky_radiance(glm::vec3 d) const;
    glm::vec3 cube_radiance(glm::vec3 d) const;

    Sky sky_;
    glm::vec3 sun_ = glm::normalize(Sky{}.sun_direction);
    std::array<FloatImage, 6> faces_;
};

}  // namespace tessera::march
