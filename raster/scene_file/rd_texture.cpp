#include "raster/scene_file/rd_texture.h"

#include "procedural/rd_color.h"
#include "procedural/rd_initial.h"
#include "procedural/rd_presets.h"

namespace tessera::scene_file {

namespace tp = tessera::procedural;

tp::ReactionDiffusion rd_simulation(const TextureSpec& t) {
    const tp::RdPreset* preset = tp::find_rd_preset(t.preset);
    tp::GrayScott params;
    params.feed = preset->feed;
    params.kill = preset->kill;
    params.anisotropy = t.anisotropy;
    return tp::ReactionDiffusion(params, tp::rd_initial_noise(t.size, t.size, t.seed, 12.0f));
}

texture::Texture rd_texture(const tp::RdState& state, const TextureSpec& t) {
    const std::vector<uint8_t> rgb = t.ramp.empty() ? tp::rd_colorize(state) : tp::rd_colorize(state, t.ramp);
    // rd_colorize quantises the ramp's linear values to bytes; they stay linear here.
    std::vector<glm::vec4> texels(size_t(state.a.width) * size_t(state.a.height));
    for (size_t i = 0; i < texels.size(); ++i)
        texels[i] = glm::vec4(rgb[3 * i] / 255.0f, rgb[3 * i + 1] / 255.0f, rgb[3 * i + 2] / 255.0f, 1.0f);
    return texture::Texture(state.a.width, state.a.height, std::move(texels));
}

}  // namespace tessera::scene_file
