#include "raster/shade/background_radiance.h"

#include <cmath>

#include "raster/texture/sampler.h"

namespace tessera::shade {
namespace {

// The weight of the zenith colour at elevation sine `up` >= 0: sqrt(up), whose slope is
// infinite at the horizon, eased in over the lowest kHorizonBand by smoothstep so that its
// slope is 0 there. A kink in the sky's gradient is a bright line at the horizon, and a curved
// mirror (the metaballs' reflections) shows it as a crease.
constexpr float kHorizonBand = 0.1f;  // sine of the elevation, about 5.7 degrees
constexpr float kGroundBand = 0.25f;  // below the horizon, down to the ground colour

glm::vec3 sky_radiance(const scene::Sky& sky, glm::vec3 d) {
    const float up = d.y;
    glm::vec3 c = up >= 0.0f
                      ? glm::mix(sky.horizon, sky.zenith, std::sqrt(up) * glm::smoothstep(0.0f, kHorizonBand, up))
                      : glm::mix(sky.horizon, sky.ground, glm::smoothstep(0.0f, kGroundBand, -up));
    const float len = glm::length(sky.sun_direction);
    if (len > 0.0f) {
        const float cosine = glm::dot(d, sky.sun_direction / len);
        if (cosine > 0.9995f) return sky.sun;  // a disc of about 1.8 degrees
        if (cosine > 0.0f) c += sky.sun * (0.02f * std::pow(cosine, 64.0f));  // glow
    }
    return c;
}

glm::vec3 cube_radiance(const scene::CubeMap& cube, glm::vec3 d) {
    const glm::vec3 a = glm::abs(d);
    int face;
    float sc, tc, ma;
    if (a.x >= a.y && a.x >= a.z) {
        face = d.x >= 0.0f ? 0 : 1;
        sc = d.x >= 0.0f ? -d.z : d.z;
        tc = -d.y;
        ma = a.x;
    } else if (a.y >= a.z) {
        face = d.y >= 0.0f ? 2 : 3;
        sc = d.x;
        tc = d.y >= 0.0f ? d.z : -d.z;
        ma = a.y;
    } else {
        face = d.z >= 0.0f ? 4 : 5;
        sc = d.z >= 0.0f ? d.x : -d.x;
        tc = -d.y;
        ma = a.z;
    }
    const texture::Texture* texture = cube.faces[size_t(face)].get();
    if (!texture || !(ma > 0.0f)) return glm::vec3(0.0f);
    const float s = 0.5f * (sc / ma + 1.0f), t = 0.5f * (tc / ma + 1.0f);
    return glm::vec3(texture::sample(*texture, {s, 1.0f - t}, {}, texture::TextureFilter::bilinear, texture::TextureWrap::clamp));
}

}  // namespace

glm::vec3 background_radiance(const scene::Background& background, glm::vec3 direction) {
    const float len = glm::length(direction);
    const glm::vec3 d = len > 0.0f && std::isfinite(len) ? direction / len : glm::vec3(0, 0, -1);
    switch (background.kind) {
        case scene::Background::Kind::colour: return background.colour;
        case scene::Background::Kind::sky: return sky_radiance(background.sky, d);
        case scene::Background::Kind::cube_map: return cube_radiance(background.cube, d);
    }
    return background.colour;
}

}  // namespace tessera::shade
