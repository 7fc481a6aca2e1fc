// A texture: RGBA float texels in linear light plus its mip-map chain ("mip-map,
// multum in parvo"), ready for the sampler (sampler.h).
//
// Orientation follows OpenGL and OBJ: texel row 0 is v = 0, the BOTTOM of an image file, and
// u grows to the right; loading flips the file's top-to-bottom rows accordingly. Level k is
// max(1, floor(w / 2^k)) x max(1, floor(h / 2^k)), down to 1 x 1; every size is legal
// (non-powers of two and 1 x 1 included).
#pragma once
#include <glm/glm.hpp>

#include <cstdint>
#include <filesystem>
#include <span>
#include <vector>

#include "raster/io/image_io.h"

namespace tessera::texture {

// One level of the chain: a view into the texture's storage (valid while the texture lives).
struct MipLevel {
    int width = 0;
    int height = 0;
    std::span<const glm::vec4> texels;  // row-major, row 0 = v = 0
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
    // positive, does not match the texel count, or the whole chain exceeds 2^28 texels (the
    // sampler's 32-bit gather indices address 4 floats per texel).
    Texture(int width, int height, std::vector<glm::vec4> texels);

    // Converts an image read by read_image: 1 channel -> grey, 2 -> grey + alpha, 3 -> RGB,
    // 4 -> RGBA (more channels: the first four); rows flipped so that row 0 is the bottom.
    static Texture from_image(const io::FloatImage& image, TexelEncoding encoding);

    int width() const { return widths_.front(); }
    int height() const { return heights_.front(); }
    int level_count() const { return int(widths_.size()); }
    MipLevel level(int index) const;

    // The packed storage the SIMD sampler gathers from: every level's texels back to back,
    // level k starting at texel offsets()[k] with widths()[k] x heights()[k] texels.
    const glm::vec4* texels() const { return texels_.data(); }
    const int32_t* widths() const { return widths_.data(); }
    const int32_t* heights() const { return heights_.data(); }
    const int32_t* offsets() const { return offsets_.data(); }

private:
    std::vector<glm::vec4> texels_;
    std::vector<int32_t> widths_, heights_, offsets_;
};

// Reads an image file as a texture. Throws tessera::Error naming the file and the reason
// (a missing or unreadable texture is a clear error, never a crash).
Texture load_texture(const std::filesystem::path& path, TexelEncoding encoding);

}  // namespace tessera::texture
