#include "raster/march/fog_pass.h"

#include <cmath>

namespace tessera::march {

FogPass::FogPass(const RayGenerator& rays, const Fog& fog) : rays_(rays), fog_(fog) {
    fog_.validate();
}

namespace {

constexpr float kFarFadeStart = 0.75f;  // of the far distance

// 1 up to kFarFadeStart of the far distance, 0 at the far plane, smooth between. The
// background (infinitely far) keeps the closed form: high fog seen upwards lets the sky through.
float far_visibility(float distance, float far_distance) {
    if (std::isinf(distance)) return 1.0f;
    if (!(distance < far_distance)) return 0.0f;
    return 1.0f - glm::smoothstep(kFarFadeStart, 1.0f, distance / far_distance);
}

}  // namespace

void FogPass::run(const Tile& target) const {
    if (!fog_.enabled()) return;
    for (int y = target.rect.y0; y < target.rect.y1; ++y)
        for (int x = target.rect.x0; x < target.rect.x1; ++x) {
            if (!target.active(x, y)) continue;
            glm::vec4& c = target.colour_at(x, y);
            const glm::vec3 d = rays_.direction(x, y);
            const float distance = rays_.distance_from_depth(x, y, target.depth_at(x, y));
            const glm::vec3 t = fog_.transmittance(rays_.eye(), d, distance) *
                                far_visibility(distance, rays_.far_distance(d));
            c = glm::vec4(t * glm::vec3(c) + (1.0f - t) * fog_.colour, c.a);
        }
}

}  // namespace tessera::march
