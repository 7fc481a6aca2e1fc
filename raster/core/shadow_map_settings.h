// How a light's shadow maps are made (--shadows map): a plain record that the scene keeps per
// light and the shadow layer turns into maps (shadow/shadow_map.h, shadow/cascades.h). It
// lives here, below both, so a scene file can carry it without the scene depending on the
// shadow code.
#pragma once

namespace tessera {

struct ShadowMapSettings {
    // Texels along each side of every cascade's square map, 16 .. 8192 (the rasterizer's
    // viewport limit).
    int resolution = 2048;
    // Cascades split along the camera's view, 1 .. 8; 1: one map over what the camera sees.
    int cascades = 4;
    // The practical split scheme's blend between logarithmic (1) and uniform (0) splits.
    float split_blend = 0.8f;
    // Percentage-closer filtering: (2r+1)^2 taps, 0 .. 8.
    int pcf_radius = 1;
    // Receiver offset along its normal, in texels of the cascade it reads, times sin(theta).
    float normal_offset = 1.6f;
    // Receiver offset towards the light, in texels.
    float depth_bias = 0.5f;

    bool operator==(const ShadowMapSettings&) const = default;
};

// Throws std::invalid_argument naming the first value out of range (and its range).
void check_shadow_map_settings(const ShadowMapSettings& settings);

}  // namespace tessera
