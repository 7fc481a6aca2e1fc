// The shadow-map flags of `render`, `raster` and `shadows`: each flag given overrides that
// setting of every light (a scene file sets them per light, "shadow_map" in a light).
#pragma once
#include <CLI/CLI.hpp>

#include <optional>
#include <span>

#include "raster/core/shadow_map_settings.h"
#include "raster/scene/light.h"

namespace tessera::cli {

struct ShadowMapFlags {
    std::optional<int> resolution, cascades, pcf_radius;
    std::optional<float> split_blend, normal_offset, depth_bias;

    void apply(ShadowMapSettings& settings) const;
    void apply(std::span<scene::Light> lights) const;
};

// --map-size, --cascades, --split-blend, --pcf, --normal-offset, --depth-bias, each checked
// against its range (core/shadow_map_settings.h).
void add_shadow_map_options(CLI::App& command, ShadowMapFlags& flags);

}  // namespace tessera::cli
