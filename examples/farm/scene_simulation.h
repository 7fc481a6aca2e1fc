// Scene state that depends on earlier frames: growing reaction-diffusion skins
// (TextureSpec::grow_per_frame > 0). The state of frame f is a pure function of f (each
// skin has run steps + grow_per_frame * f Gray-Scott steps, and the simulation is
// bit-identical however steps are split, reaction_diffusion.h), so any process that reaches
// frame f, by simulating from step 0 or by restoring a checkpoint of an earlier frame and
// simulating on, holds the same bytes and renders the same frame.
//
// A checkpoint is the full state (every skin's A and B grids and step count) with a
// fingerprint of the parameters that produced it, so a checkpoint of another scene version
// is never restored, and a checksum, so a damaged file is rejected rather than rendered.
#pragma once
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "procedural/reaction_diffusion.h"
#include "raster/render/animated_scene.h"
#include "raster/scene_file/scene_spec.h"

namespace tessera::farm {

class SceneSimulation {
public:
    // The growing skins among a scene's textures (in the scene's texture order), at step 0
    // (no frame yet).
    explicit SceneSimulation(std::span<const scene_file::TextureSpec> textures);

    bool empty() const { return skins_.empty(); }
    // The frame whose state is held; nullopt before the first advance or restore.
    std::optional<int> frame() const { return frame_; }

    // Simulates forward to `frame` (frame >= 0). A frame before the one held starts over
    // from step 0 (callers restore a checkpoint first to avoid that).
    void advance_to(int frame);

    // Puts the held state's colours into the scene's textures.
    void apply(render::AnimatedScene& scene) const;

    // Parameters of every skin (preset rates, size, seed, steps, growth, anisotropy) and the
    // checkpoint format version, hashed.
    uint64_t fingerprint() const { return fingerprint_; }

    std::vector<std::byte> checkpoint() const;
    // Throws tessera::Error (naming `what`, e.g. the file) for a truncated, damaged or
    // foreign checkpoint; the held state is unchanged then.
    void restore(std::span<const std::byte> bytes, const std::string& what);

    // Bytes of one checkpoint (for sizing the checkpoint store).
    size_t checkpoint_size() const;

private:
    struct Skin {
        size_t texture;  // index into the scene's textures (= the spec's texture order)
        scene_file::TextureSpec spec;
        procedural::ReactionDiffusion rd;
        int64_t steps = 0;  // steps the held state has run
        int64_t steps_for(int frame) const { return int64_t(spec.steps) + int64_t(spec.grow_per_frame) * frame; }
    };
    std::vector<Skin> skins_;
    std::optional<int> frame_;
    uint64_t fingerprint_ = 0;
};

}  // namespace tessera::farm
