#include "raster/march/fog_pass.h"

namespace tessera::march {

FogPass::FogPass(const RayGenerator& rays, const Fog& fog) : rays_(rays), fog_(fog) {
    fog_.validate();
}

void FogPass::run(const Tile& target) const {
    if (!fog_.enabled()) return;
    for (int y = target.rect.y0; y < target.rect.y1; ++y)
        for (int x = target.rect.x0; x < target.rect.x1; ++x) {
            if (!target.active(x, y)) continue;
            glm::vec4& c = target.colour_at(x, y);
            const float distance = rays_.distance_from_depth(x, y, target.depth_at(x, y));
            const glm::vec3 seen = fog_.apply(glm::vec3(c), rays_.eye(), rays_.direction(x, y), distance);
            c = glm::vec4(seen, c.a);
        }
}

}  // namespace tessera::march
