#include "examples/render_farm.h"

#include <cmath>

#include "examples/command.h"
#include "raster/io/image_completeness.h"

namespace tessera::cli {

namespace fs = std::filesystem;

void add_farm_options(CLI::App& cmd, FarmOptions& o) {
    cmd.add_flag("--claim", o.claim,
                 "Claim each frame with a placeholder file first, so processes sharing the output folder never "
                 "render a frame twice");
    cmd.add_option("--claim-timeout", o.claim_timeout,
                   "With --resume and --claim: take over claims older than this many seconds (0: only claims of "
                   "dead processes on this host)")
        ->capture_default_str();
    cmd.add_option("--checkpoint-every", o.checkpoint_every,
                   "Save simulated state (growing skins) every K frames, so a later start restores it (0: never)")
        ->capture_default_str();
    cmd.add_option("--checkpoints", o.checkpoints, "Checkpoint folder (default: OUTDIR/.tessera-sim)");
    cmd.add_option("--distribute", o.distribute,
                   "Under mpirun: frames (rank 0 hands out frames) or tiles (bands of each frame, gathered)")
        ->check(CLI::IsMember({"frames", "tiles"}));
}

FarmRun::FarmRun(const FarmOptions& o, bool resume, render::AnimatedScene& scene, std::span<const scene_file::TextureSpec> textures,
                 const std::string& scene_name, const fs::path& output_folder)
    : claims_(o.claim), scene_(scene), simulation_(textures) {
    if (!(o.claim_timeout >= 0.0) || !std::isfinite(o.claim_timeout))
        throw UsageError("--claim-timeout must be a non-negative number of seconds");
    if (o.checkpoint_every < 0) throw UsageError("--checkpoint-every must be 0 or more");
    policy_.take_over_stale = resume;
    policy_.stale_after_s = o.claim_timeout;
    if (!simulation_.empty()) {
        const fs::path dir = !o.checkpoints.empty() ? fs::path(o.checkpoints) : output_folder / ".tessera-sim";
        store_ = std::make_unique<farm::CheckpointStore>(dir, scene_name, simulation_.fingerprint(), o.checkpoint_every);
    }
}

FarmRun::~FarmRun() {
    for (const fs::path& p : held_) farm::release_claim(p);
}

bool FarmRun::claim(const fs::path& frame, int width, int height) {
    if (!claims_) return true;
    const farm::ClaimResult result = farm::try_claim(frame, policy_);
    if (result == farm::ClaimResult::held) {
        ++held_elsewhere_;
        return false;
    }
    if (io::image_is_complete(frame, width, height)) {
        farm::release_claim(frame);
        return false;
    }
    held_.insert(frame);
    if (result == farm::ClaimResult::claimed) return true;
    // A claim taken over from a dead owner may find its half-written temporary
    // (atomic_file.h: ".NAME.tmpPID_N"): nobody else writes this frame now, so it goes.
    std::error_code ec;
    const fs::path dir = frame.parent_path().empty() ? fs::path(".") : frame.parent_path();
    const std::string temporary = "." + frame.filename().string() + ".tmp";
    std::vector<fs::path> stale;
    for (const auto& entry : fs::directory_iterator(dir, ec))
        if (entry.path().filename().string().rfind(temporary, 0) == 0) stale.push_back(entry.path());
    for (const fs::path& p : stale) fs::remove(p, ec);
    return true;
}

void FarmRun::simulate(int number) {
    if (simulation_.empty()) return;
    frames_simulated_ += farm::advance(simulation_, store_.get(), number);
    simulation_.apply(scene_);
}

void FarmRun::published(const std::vector<fs::path>& written) {
    for (; seen_written_ < written.size(); ++seen_written_)
        if (held_.erase(written[seen_written_])) farm::release_claim(written[seen_written_]);
}

}  // namespace tessera::cli
