#include "raster/scene/background.h"

#include <stdexcept>

#include "raster/core/error.h"

namespace tessera::scene {

CubeMap load_cube_map(const std::string& pattern) {
    static const char* const kNames[6] = {"px", "nx", "py", "ny", "pz", "nz"};
    const size_t at = pattern.find("{face}");
    if (at == std::string::npos)
        throw std::invalid_argument("cube map pattern '" + pattern + "' needs a {face} placeholder");
    CubeMap cube;
    for (int i = 0; i < 6; ++i) {
        std::string path = pattern;
        path.replace(at, 6, kNames[i]);
        cube.faces[size_t(i)] = std::make_shared<const texture::Texture>(texture::load_texture(path, texture::TexelEncoding::srgb));
    }
    return cube;
}

}  // namespace tessera::scene
