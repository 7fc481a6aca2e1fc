// A reaction-diffusion texture (TextureSpec::Kind::reaction_diffusion) in two halves: the
// simulation it grows from (Gray-Scott with the preset's feed and kill, seeded noise) and the
// colours of a simulation state through the texture's ramp. A static skin is the state after
// `steps` steps; a growing skin (grow_per_frame > 0) is re-coloured every frame from a
// simulation that keeps running (farm/scene_simulation.h).
#pragma once
#include "procedural/reaction_diffusion.h"
#include "raster/scene_file/scene_spec.h"
#include "raster/texture/texture.h"

namespace tessera::scene_file {

// The simulation at step 0 (the initial noise), validated.
procedural::ReactionDiffusion rd_simulation(const TextureSpec& t);

// The state's colours (A - B through the ramp, quantised to bytes as rd_colorize does, kept
// linear).
texture::Texture rd_texture(const procedural::RdState& state, const TextureSpec& t);

}  // namespace tessera::scene_file
