// Simulation checkpoints on disk, POV-Ray's .pov-state for growing skins: every `every`
// frames (absolute frame numbers, so every shard and rank agrees which frames those are) the
// state is written, atomically, as DIR/SCENE-FINGERPRINT-FRAME.sim. A process that needs
// frame k restores the latest checkpoint at or before k and simulates only the frames after
// it, so a shard starting at frame k costs at most `every` frames of re-simulation once any
// process has passed the checkpoint before k. Concurrent writers of one checkpoint write the
// same bytes (the state is a pure function of the frame), so the last rename wins harmlessly.
#pragma once
#include <filesystem>
#include <optional>
#include <string>

#include "examples/farm/scene_simulation.h"

namespace tessera::farm {

class CheckpointStore {
public:
    // every = 0: no checkpoints are written (existing ones are still restored).
    CheckpointStore(std::filesystem::path dir, std::string scene, uint64_t fingerprint, int every);

    std::filesystem::path path_for(int frame) const;
    bool due(int frame) const { return every_ > 0 && frame % every_ == 0; }
    // The latest checkpoint frame c with after < c <= up_to, if any.
    std::optional<int> latest(int after, int up_to) const;

    // Throws tessera::Error when the directory or file cannot be written.
    void save(int frame, const SceneSimulation& simulation) const;

private:
    std::filesystem::path dir_;
    std::string prefix_;  // "SCENE-FINGERPRINT-"
    int every_;
};

// Brings `simulation` to `frame` as cheaply as the checkpoints allow: restores the latest
// checkpoint between the held frame (or the start) and `frame` when one exists, then
// simulates frame by frame, saving each checkpoint that is due and missing on the way.
// A damaged checkpoint is reported on stderr and skipped (the state is simulated instead).
// Returns the number of frames simulated (0: restored or already there).
int advance(SceneSimulation& simulation, const CheckpointStore* store, int frame);

}  // namespace tessera::farm
