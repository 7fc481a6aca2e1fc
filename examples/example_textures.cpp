#include "examples/example_textures.h"

#include "procedural/heightfield.h"
#include "procedural/normal_map.h"
#include "procedural/rd_color.h"
#include "procedural/rd_initial.h"
#include "procedural/rd_presets.h"
#include "procedural/reaction_diffusion.h"
#include "raster/image_io.h"

namespace tessera::examples {

namespace tp = tessera::procedural;

Texture reaction_diffusion_texture(const char* preset, int size, int steps, uint32_t seed) {
    const tp::RdPreset* p = tp::find_rd_preset(preset);
    tp::GrayScott params;
    if (p) {
        params.feed = p->feed;
        params.kill = p->kill;
    }
    tp::ReactionDiffusion rd(params, tp::rd_initial_spots(size, size, seed));
    rd.step(steps);
    const std::vector<uint8_t> rgb = tp::rd_colorize(rd.state());
    FloatImage image;
    image.width = image.height = size;
    image.channels = 3;
    image.pixels.reserve(rgb.size());
    for (uint8_t c : rgb) image.pixels.push_back(float(c) / 255.0f);  // the ramp is linear
    return Texture::from_image(image, TexelEncoding::linear);
}

tp::Grid heightfield_grid(int size, uint32_t seed, int cells) {
    tp::HeightfieldParams params;
    params.fractal.seed = seed;
    params.fractal.octaves = 6;
    params.cells = cells;
    return tp::generate_heightfield(size, size, params);
}

Texture normal_map_texture(const tp::Grid& heights, float strength) {
    const tp::NormalMap normals = tp::normal_map(heights, strength, tp::Boundary::periodic);
    FloatImage image;
    image.width = normals.width;
    image.height = normals.height;
    image.channels = 3;
    image.pixels.reserve(normals.xyz.size());
    for (float c : normals.xyz) image.pixels.push_back(c * 0.5f + 0.5f);  // seeds/004 encoding
    return Texture::from_image(image, TexelEncoding::linear);
}

}  // namespace tessera::examples
