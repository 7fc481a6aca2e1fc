#include "procedural/rd_initial.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "procedural/hash.h"
#include "procedural/noise.h"

namespace tessera::procedural {

namespace {
constexpr float kSeedA = 0.5f, kSeedB = 0.25f;  // Pearson (1993)
}

RdState rd_initial_spots(int width, int height, uint32_t seed, int count, int radius) {
    check_grid_size(width, height, "reaction-diffusion grid");
    RdState s{Grid(width, height, 1.0f), Grid(width, height, 0.0f)};
    if (count <= 0) count = std::max(1, int(int64_t(width) * height / 4096));
    radius = std::max(radius, 1);
    for (int i = 0; i < count; ++i) {
        const int cx = int(unit_float(hash(seed, i, 0)) * float(width));
        const int cy = int(unit_float(hash(seed, i, 1)) * float(height));
        for (int dy = -radius; dy <= radius; ++dy)
            for (int dx = -radius; dx <= radius; ++dx) {
                if (dx * dx + dy * dy > radius * radius) continue;
                const int x = ((cx + dx) % width + width) % width;
                const int y = ((cy + dy) % height + height) % height;
                s.a.at(x, y) = kSeedA;
                s.b.at(x, y) = kSeedB;
            }
    }
    return s;
}

RdState rd_initial_noise(int width, int height, uint32_t seed, float scale) {
    check_grid_size(width, height, "reaction-diffusion grid");
    if (!(scale >= 1.0f && scale <= 1e6f))
        throw std::invalid_argument("noise seeding scale must be a number >= 1 (cells)");
    RdState s{Grid(width, height, 1.0f), Grid(width, height, 0.0f)};
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const float n = value_noise(glm::vec2(float(x), float(y)) / scale, seed).value;
            if (n > 0.45f) {
                s.a.at(x, y) = kSeedA;
                s.b.at(x, y) = kSeedB;
            }
        }
    return s;
}

RdState rd_initial_image(const Grid& image) {
    check_grid_size(image.width, image.height, "seed image");
    RdState s{Grid(image.width, image.height, 1.0f), Grid(image.width, image.height, 0.0f)};
    for (size_t i = 0; i < image.size(); ++i) {
        const float v = image.values[i];
        if (!std::isfinite(v)) throw std::invalid_argument("seed image has non-finite values");
        const float c = std::clamp(v, 0.0f, 1.0f);
        s.a.values[i] = 1.0f - (1.0f - kSeedA) * c;
        s.b.values[i] = kSeedB * c;
    }
    return s;
}

}  // namespace tessera::procedural
