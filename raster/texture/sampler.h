// Texture filtering: nearest, bilinear, mip-mapped, trilinear, with repeat or clamp wrapping.
//
// The mip level comes from the screen-space derivatives of (u, v), which the shading stage
// computes analytically from the triangle's plane equations (not from neighbouring pixels):
// with the texel-space footprint of one pixel step in x and y,
//     rho = max(|(du/dx * w, dv/dx * h)|, |(du/dy * w, dv/dy * h)|),  lambda = log2(rho)
// (the OpenGL 4.6 specification, section 8.14). lambda <= 0 is magnification.
#pragma once
#include <glm/glm.hpp>

#include <cstdint>

#include "raster/texture/texture.h"

namespace tessera::texture {

// nearest and bilinear read the full-resolution level (GL_NEAREST, GL_LINEAR); mipmap reads
// the nearest mip level bilinearly (GL_LINEAR_MIPMAP_NEAREST); trilinear blends the two
// nearest levels (GL_LINEAR_MIPMAP_LINEAR).
enum class TextureFilter : uint8_t { nearest, bilinear, mipmap, trilinear };
enum class TextureWrap : uint8_t { repeat, clamp };

// Derivatives of the texture coordinates with respect to window x and y (pixels).
struct UvDerivatives {
    glm::vec2 d_dx{0.0f};
    glm::vec2 d_dy{0.0f};
};

// lambda of the OpenGL specification (may be negative: magnification; -inf for a zero
// footprint; +inf for infinite derivatives, which then select the coarsest level). A NaN
// derivative counts as zero along its axis.
float mip_lambda(const Texture& texture, const UvDerivatives& derivatives);

// Filtered texel at `uv` (texel centres at (i + 0.5) / width). Non-finite uv gives the
// texel at (0, 0) rather than undefined behaviour.
glm::vec4 sample(const Texture& texture, glm::vec2 uv, const UvDerivatives& derivatives,
                 TextureFilter filter, TextureWrap wrap);

}  // namespace tessera::texture
