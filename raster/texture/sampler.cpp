#include "raster/texture/sampler.h"

#include <algorithm>
#include <cmath>

namespace tessera::texture {
namespace {

// Repeat: coordinates arrive reduced to [0, 1) by safe_coordinate, so a texel index lies in
// [-1, size] and one conditional add or subtract wraps it (no integer modulo per fetch).
int wrap_index(int i, int size, TextureWrap wrap) {
    if (wrap == TextureWrap::clamp) return std::clamp(i, 0, size - 1);
    if (i < 0) i += size;
    if (i >= size) i -= size;
    return std::clamp(i, 0, size - 1);  // guards the rounding of u * size at u just below 1
}

// Large or non-finite coordinates would overflow the int conversion; reduce them first.
float safe_coordinate(float t, TextureWrap wrap) {
    if (!std::isfinite(t)) return 0.0f;
    if (wrap == TextureWrap::repeat) return t - std::floor(t);
    return std::clamp(t, -1.0f, 2.0f);
}

glm::vec4 nearest(const MipLevel& level, glm::vec2 uv, TextureWrap wrap) {
    const int x = wrap_index(int(std::floor(uv.x * float(level.width))), level.width, wrap);
    const int y = wrap_index(int(std::floor(uv.y * float(level.height))), level.height, wrap);
    return level.at(x, y);
}

glm::vec4 bilinear(const MipLevel& level, glm::vec2 uv, TextureWrap wrap) {
    const float fx = uv.x * float(level.width) - 0.5f;
    const float fy = uv.y * float(level.height) - 0.5f;
    const float x0f = std::floor(fx), y0f = std::floor(fy);
    const float ax = fx - x0f, ay = fy - y0f;
    const int x0 = wrap_index(int(x0f), level.width, wrap);
    const int x1 = wrap_index(int(x0f) + 1, level.width, wrap);
    const int y0 = wrap_index(int(y0f), level.height, wrap);
    const int y1 = wrap_index(int(y0f) + 1, level.height, wrap);
    const glm::vec4 bottom = glm::mix(level.at(x0, y0), level.at(x1, y0), ax);
    const glm::vec4 top = glm::mix(level.at(x0, y1), level.at(x1, y1), ax);
    return glm::mix(bottom, top, ay);
}

}  // namespace

float mip_lambda(const Texture& texture, const UvDerivatives& d) {
    const glm::vec2 size(float(texture.width()), float(texture.height()));
    const float along_x = glm::length(d.d_dx * size), along_y = glm::length(d.d_dy * size);
    // A NaN derivative (a degenerate triangle's) counts as no footprint along that axis.
    const float rho = std::max(std::isnan(along_x) ? 0.0f : along_x, std::isnan(along_y) ? 0.0f : along_y);
    return std::log2(rho);
}

glm::vec4 sample(const Texture& texture, glm::vec2 uv, const UvDerivatives& derivatives,
                 TextureFilter filter, TextureWrap wrap) {
    uv = {safe_coordinate(uv.x, wrap), safe_coordinate(uv.y, wrap)};
    if (filter == TextureFilter::nearest) return nearest(texture.level(0), uv, wrap);
    if (filter == TextureFilter::bilinear) return bilinear(texture.level(0), uv, wrap);

    const float top = float(texture.level_count() - 1);
    const float lambda = std::clamp(mip_lambda(texture, derivatives), 0.0f, top);
    if (filter == TextureFilter::mipmap)
        return bilinear(texture.level(int(std::floor(lambda + 0.5f))), uv, wrap);
    const int lower = int(std::floor(lambda));
    const int upper = std::min(lower + 1, int(top));
    const float t = lambda - float(lower);
    return glm::mix(bilinear(texture.level(lower), uv, wrap), bilinear(texture.level(upper), uv, wrap), t);
}

}  // namespace tessera::texture
