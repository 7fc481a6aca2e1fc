#include "examples/shadow_map_flags.h"

namespace tessera::cli {

void ShadowMapFlags::apply(ShadowMapSettings& s) const {
    if (resolution) s.resolution = *resolution;
    if (cascades) s.cascades = *cascades;
    if (pcf_radius) s.pcf_radius = *pcf_radius;
    if (split_blend) s.split_blend = *split_blend;
    if (normal_offset) s.normal_offset = *normal_offset;
    if (depth_bias) s.depth_bias = *depth_bias;
}

void ShadowMapFlags::apply(std::span<scene::Light> lights) const {
    for (scene::Light& light : lights) apply(light.shadow_map);
}

void add_shadow_map_options(CLI::App& command, ShadowMapFlags& flags) {
    const ShadowMapSettings d;
    const auto was = [](auto value) { return " (default " + CLI::detail::to_string(value) + ", or the scene's)"; };
    command.add_option("--map-size", flags.resolution, "Shadow map texels a side, per cascade" + was(d.resolution))
        ->check(CLI::Range(16, 8192));
    command.add_option("--cascades", flags.cascades, "Shadow map cascades along the view" + was(d.cascades))
        ->check(CLI::Range(1, 8));
    command.add_option("--split-blend", flags.split_blend,
                       "Cascade splits: 1 logarithmic, 0 uniform, between: blended" + was(d.split_blend))
        ->check(CLI::Range(0.0f, 1.0f));
    command.add_option("--pcf", flags.pcf_radius, "PCF radius r: (2r+1)^2 box of taps" + was(d.pcf_radius))
        ->check(CLI::Range(0, 8));
    command.add_option("--normal-offset", flags.normal_offset,
                       "Shadow bias along the normal, texels times sin(theta)" + was(d.normal_offset))
        ->check(CLI::Range(0.0f, 64.0f));
    command.add_option("--depth-bias", flags.depth_bias, "Shadow bias towards the light, texels" + was(d.depth_bias))
        ->check(CLI::Range(0.0f, 64.0f));
}

}  // namespace tessera::cli
