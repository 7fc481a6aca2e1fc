// A 3-D noise surface from procedural/'s gradient (Perlin-style) noise, the second of the classic
// "3-D noise instead of a heightfield" surfaces (overhangs, bridges):
//     f(p) = base + amplitude * n(frequency * p) - p.y,
//     grad f = amplitude * frequency * grad n - (0, 1, 0),
// with n and grad n from procedural::gradient_noise. Positive below the undulating ground.
#pragma once
#include <glm/glm.hpp>

#include <cstdint>

#include "procedural/noise.h"
#include "raster/march/ray_packet.h"

namespace tessera::march {

struct GradientNoiseField {
    float frequency = 1.5f;
    float amplitude = 0.5f;
    float base = 0.5f;
    uint32_t seed = 7;

    float value(glm::vec3 p) const {
        return base + amplitude * procedural::gradient_noise(p * frequency, seed).value - p.y;
    }
    glm::vec3 gradient(glm::vec3 p) const {
        return (amplitude * frequency) * procedural::gradient_noise(p * frequency, seed).gradient -
               glm::vec3(0.0f, 1.0f, 0.0f);
    }
    // The packet forms through procedural's SIMD batch, equal to value() and gradient() at
    // each point bit for bit (the same noise at the same scaled point, finished the same way).
    void values(const float* x, const float* y, const float* z, float* out) const {
        alignas(64) float sx[kMarchLanes], sy[kMarchLanes], sz[kMarchLanes], n[kMarchLanes];
        scaled(x, y, z, sx, sy, sz);
        procedural::gradient_noise_batch(seed, kMarchLanes, sx, sy, sz, n);
        for (int i = 0; i < kMarchLanes; ++i) out[i] = base + amplitude * n[i] - y[i];
    }
    void gradients(const float* x, const float* y, const float* z, float* gx, float* gy, float* gz) const {
        alignas(64) float sx[kMarchLanes], sy[kMarchLanes], sz[kMarchLanes], n[kMarchLanes];
        scaled(x, y, z, sx, sy, sz);
        procedural::gradient_noise_batch(seed, kMarchLanes, sx, sy, sz, n, gx, gy, gz);
        for (int i = 0; i < kMarchLanes; ++i) {
            const glm::vec3 g = (amplitude * frequency) * glm::vec3(gx[i], gy[i], gz[i]) - glm::vec3(0.0f, 1.0f, 0.0f);
            gx[i] = g.x;
            gy[i] = g.y;
            gz[i] = g.z;
        }
    }

private:
    void scaled(const float* x, const float* y, const float* z, float* sx, float* sy, float* sz) const {
        for (int i = 0; i < kMarchLanes; ++i) {
            const glm::vec3 p = glm::vec3(x[i], y[i], z[i]) * frequency;
            sx[i] = p.x;
            sy[i] = p.y;
            sz[i] = p.z;
        }
    }
};

}  // namespace tessera::march
