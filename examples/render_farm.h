// What `tessera render` adds for farms (several processes or machines, one output folder):
//   --claim               claim each frame with a placeholder before rendering it
//                         (raster/farm/frame_claim.h), so processes sharing the folder never
//                         render a frame twice; with --resume, claims of dead processes (same
//                         host) or older than --claim-timeout are taken over;
//   --checkpoint-every K  simulated state (growing skins) saved every K frames under
//   --checkpoints DIR     (default: OUTDIR/.tessera-sim), restored by any later process;
//   --distribute MODE     MPI frames or tiles (distribute.h).
#pragma once
#include <CLI/CLI.hpp>

#include <filesystem>
#include <memory>
#include <span>
#include <set>
#include <string>
#include <vector>

#include "examples/farm/checkpoint_store.h"
#include "examples/farm/frame_claim.h"
#include "examples/farm/scene_simulation.h"

namespace tessera::cli {

struct FarmOptions {
    bool claim = false;
    double claim_timeout = 0.0;
    int checkpoint_every = 24;
    std::string checkpoints;
    std::string distribute;
};

void add_farm_options(CLI::App& command, FarmOptions& options);

// One process's share of the farm protocol around each frame it renders.
class FarmRun {
public:
    // Throws UsageError for bad values. `textures`: the specs `scene`'s textures were built
    // from, in order (the growing ones are simulated). The default checkpoint folder is
    // OUTPUT_FOLDER/.tessera-sim.
    FarmRun(const FarmOptions& options, bool resume, render::AnimatedScene& scene, std::span<const scene_file::TextureSpec> textures,
            const std::string& scene_name, const std::filesystem::path& output_folder);
    ~FarmRun();  // hands back claims of frames never written (so others need not wait)

    // Whether this process renders `frame` now: true without --claim; with it, true only if
    // the claim is won and the frame is still not complete (another process may have
    // published it between the caller's check and the claim).
    bool claim(const std::filesystem::path& frame, int width, int height);
    // The scene's simulated state at frame `number` (restoring checkpoints where they help).
    void simulate(int number);
    // Releases the claims of frames now on disk. `written`: the writer's list of written
    // paths so far (FrameWriter::written(), which only grows), read from where the last call
    // stopped.
    void published(const std::vector<std::filesystem::path>& written);

    int held_elsewhere() const { return held_elsewhere_; }
    int frames_simulated() const { return frames_simulated_; }

private:
    bool claims_;
    farm::ClaimPolicy policy_;
    render::AnimatedScene& scene_;
    farm::SceneSimulation simulation_;
    std::unique_ptr<farm::CheckpointStore> store_;
    std::set<std::filesystem::path> held_;
    size_t seen_written_ = 0;
    int held_elsewhere_ = 0;
    int frames_simulated_ = 0;
};

}  // namespace tessera::cli
