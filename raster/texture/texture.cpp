#include "raster/texture/texture.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "raster/core/color_space.h"

namespace tessera::texture {
namespace {

// One tap of a 1-D box filter: source index and weight.
struct Tap {
    int source;
    float weight;
};

// Box-filter weights for shrinking `from` samples to `to` (to <= from): destination sample i
// covers the source interval [i*r, (i+1)*r) with r = from/to, and each source texel [j, j+1)
// contributes its overlap with it, divided by r. For even sizes this is the classic 2x2
// average; for odd sizes (non-power-of-two textures) the weights stay exact, so no texel is
// dropped and the mean brightness is kept on every level.
std::vector<std::vector<Tap>> box_taps(int from, int to) {
    std::vector<std::vector<Tap>> taps(static_cast<size_t>(to));
    const double r = double(from) / double(to);
    for (int i = 0; i < to; ++i) {
        const double lo = i * r, hi = (i + 1) * r;
        for (int j = int(std::floor(lo)); j < std::min(from, int(std::ceil(hi))); ++j) {
            const double overlap = std::min(hi, j + 1.0) - std::max(lo, double(j));
            if (overlap > 0.0) taps[size_t(i)].push_back({j, float(overlap / r)});
        }
    }
    return taps;
}

// The next level down from `src` into `dst` (already sized).
void half(const MipLevel& src, int width, int height, glm::vec4* dst) {
    const auto tx = box_taps(src.width, width);
    const auto ty = box_taps(src.height, height);
    tbb::parallel_for(0, height, [&](int y) {
        for (int x = 0; x < width; ++x) {
            glm::vec4 sum(0.0f);
            for (const Tap& a : ty[size_t(y)])
                for (const Tap& b : tx[size_t(x)]) sum += a.weight * b.weight * src.at(b.source, a.source);
            dst[size_t(y) * size_t(width) + size_t(x)] = sum;
        }
    });
}

}  // namespace

Texture::Texture(int width, int height, std::vector<glm::vec4> texels) {
    if (width <= 0 || height <= 0)
        throw std::invalid_argument("texture size must be positive, got " + std::to_string(width) +
                                    "x" + std::to_string(height));
    if (texels.size() != size_t(width) * size_t(height))
        throw std::invalid_argument("texture of " + std::to_string(width) + "x" +
                                    std::to_string(height) + " needs that many texels, got " +
                                    std::to_string(texels.size()));
    // Level sizes first, so the whole chain is one allocation.
    size_t total = 0;
    for (int w = width, h = height;; w = std::max(1, w / 2), h = std::max(1, h / 2)) {
        widths_.push_back(w);
        heights_.push_back(h);
        offsets_.push_back(int32_t(std::min<size_t>(total, size_t(1) << 30)));
        total += size_t(w) * size_t(h);
        if (w == 1 && h == 1) break;
    }
    if (total > (size_t(1) << 28))
        throw std::invalid_argument("texture of " + std::to_string(width) + "x" + std::to_string(height) +
                                    " is too large (the mip chain may hold at most 2^28 texels)");
    texels_ = std::move(texels);
    texels_.resize(total);
    for (size_t k = 1; k < widths_.size(); ++k)
        half(level(int(k - 1)), widths_[k], heights_[k], texels_.data() + offsets_[k]);
}

MipLevel Texture::level(int index) const {
    const size_t k = size_t(index);
    return {widths_[k], heights_[k],
            std::span<const glm::vec4>(texels_.data() + offsets_[k], size_t(widths_[k]) * size_t(heights_[k]))};
}

Texture Texture::from_image(const io::FloatImage& image, TexelEncoding encoding) {
    if (image.width <= 0 || image.height <= 0 || image.channels <= 0)
        throw std::invalid_argument("texture image is empty");
    std::vector<glm::vec4> texels(size_t(image.width) * size_t(image.height));
    const auto decode = [encoding](float v) {
        return encoding == TexelEncoding::srgb ? srgb_to_linear(v) : v;
    };
    for (int y = 0; y < image.height; ++y) {
        const int file_row = image.height - 1 - y;  // files store the top row first
        for (int x = 0; x < image.width; ++x) {
            glm::vec4 t(0.0f, 0.0f, 0.0f, 1.0f);
            const int c = image.channels;
            if (c <= 2) {
                t.r = t.g = t.b = decode(image.at(x, file_row, 0));
                if (c == 2) t.a = image.at(x, file_row, 1);
            } else {
                for (int k = 0; k < 3; ++k) t[k] = decode(image.at(x, file_row, k));
                if (c >= 4) t.a = image.at(x, file_row, 3);
            }
            texels[size_t(y) * size_t(image.width) + size_t(x)] = t;
        }
    }
    return Texture(image.width, image.height, std::move(texels));
}

Texture load_texture(const std::filesystem::path& path, TexelEncoding encoding) {
    return Texture::from_image(io::read_image(path), encoding);
}

}  // namespace tessera::texture
