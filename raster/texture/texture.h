// A texture: RGBA float texels in linear light plus its mip-map chain (seeds/000, "mip-map,
// multum in parvo"), ready for the sampler (sampler.h).
//
// Orientation follows OpenGL and OBJ: texel row 0 is v = 0, the BOTTOM of an image file, and
// u grows to the right; loading flips the file's top-to-bottom rows accordingly. Level k is
// max(1, floor(w / 2^k)) x max(1, floor(h / 2^k)), down to 1 x 1; every size is legal
// (non-powers of two and 1 x 1 included).
#pragma once
#include <glm/glm.hpp>

#include <filesystem>
#include <vector>

#include "raster/image_io.h"

namespace tessera {

struct MipLevel {
    int width = 0;
    int height = 0;
    std::vector<glm::vec4> texels;  // row-major, row 0 = v = 0
    const glm::vec4& at(int x, int y) const { return texels[size_t(y) * size_t(width) + size_t(x)]; }
};

// How the numbers in an image file are to be read.
enum class TexelEncoding {
    srgb,    // a colour picture: decode RGB to linear light (color_space.h)
    linear,  // data (normal maps, heights) or a float file: use the values as stored
};

class Texture {
public:
    // Builds the mip chain from level 0. Throws std::invalid_argument when the size is not
    // positive or does not match the texel count.
    Texture(int width, int height, std::vector<glm::vec4> texels);

    // Converts an image read by read_image: 1 channel -> grey, 2 -> grey + alpha, 3 -> RGB,
    // 4 -> RGBA (more channels: the first four); rows flipped so that row 0 is the bottom.
    static Texture from_image(const FloatImage& image, TexelEncoding encoding);

    int width() const { return levels_.front().width; }
    int height() const { return levels_.front().height; }
    int level_count() const { return int(levels_.size()); }
    const MipLevel& level(int index) const { return levels_[size_t(index)]; }

private:
    std::vector<MipLevel> levels_;
};

// Reads an image file as a texture. Throws tessera::Error naming the file and the reason
// (a missing or unreadable texture is a clear error, never a crash).
Texture load_texture(const std::filesystem::path& path, TexelEncoding encoding);

}  // namespace tessera
