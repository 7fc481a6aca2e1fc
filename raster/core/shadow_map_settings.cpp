#include "raster/core/shadow_map_settings.h"

#include <stdexcept>
#include <string>

namespace tessera {
namespace {

std::string number(float v) {
    std::string s = std::to_string(v);
    while (s.size() > 1 && s.back() == '0') s.pop_back();
    if (!s.empty() && s.back() == '.') s.pop_back();
    return s;
}

}  // namespace

void check_shadow_map_settings(const ShadowMapSettings& s) {
    // 8192: pipeline::kMaxViewport (core cannot see the pipeline layer; shadow_map.cpp
    // checks the two agree).
    if (s.resolution < 16 || s.resolution > 8192)
        throw std::invalid_argument("shadow map size " + std::to_string(s.resolution) +
                                    " is outside 16 .. 8192");
    if (s.cascades < 1 || s.cascades > 8)
        throw std::invalid_argument("shadow map cascades " + std::to_string(s.cascades) +
                                    " is outside 1 .. 8");
    if (!(s.split_blend >= 0.0f && s.split_blend <= 1.0f))
        throw std::invalid_argument("shadow map split blend " + number(s.split_blend) +
                                    " is outside 0 .. 1");
    if (s.pcf_radius < 0 || s.pcf_radius > 8)
        throw std::invalid_argument("PCF radius " + std::to_string(s.pcf_radius) + " is outside 0 .. 8");
    if (!(s.normal_offset >= 0.0f && s.normal_offset <= 64.0f))
        throw std::invalid_argument("shadow normal offset " + number(s.normal_offset) +
                                    " is outside 0 .. 64 texels");
    if (!(s.depth_bias >= 0.0f && s.depth_bias <= 64.0f))
        throw std::invalid_argument("shadow depth bias " + number(s.depth_bias) +
                                    " is outside 0 .. 64 texels");
}

}  // namespace tessera
