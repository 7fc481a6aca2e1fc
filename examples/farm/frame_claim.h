// Frame claims: several processes (or machines over a shared file system) render into one
// output folder without rendering a frame twice, Blender's "placeholders" convention made
// atomic. Before rendering frame F a process creates ".F.claim" beside the frame file with
// O_CREAT|O_EXCL, which exactly one creator wins (NFSv3+ and local file systems implement
// exclusive create atomically). The claim holds "host pid unix-time" so that a claim whose
// owner died can be recognised: same host and no such pid, or older than a configured age.
// The frame itself is published by atomic rename (atomic_file.h) BEFORE its claim is
// removed, so "frame complete or claimed" is true from the first claim onwards.
//
// Taking over a stale claim renames it to a unique name first (only one process's rename of
// a given file succeeds) and checks that what it moved is the stale claim it judged, so two
// processes breaking the same stale claim do not both win.
#pragma once
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

namespace tessera::farm {

struct ClaimOwner {
    std::string host;
    int64_t pid = 0;
    int64_t time = 0;  // seconds since the epoch when the claim was made

    // "host pid time" (one line); parse() returns nullopt for anything else (a claim being
    // written this instant is empty, and is treated as fresh).
    std::string text() const;
    static std::optional<ClaimOwner> parse(const std::string& text);
};

// This process: gethostname(), getpid(), now.
ClaimOwner current_owner();

struct ClaimPolicy {
    // Take over claims whose owner is gone (same host, pid not running) or older than
    // stale_after_s seconds (0: age alone never makes a claim stale). Off: claims are
    // respected whatever their age (a run without --resume never steals work).
    bool take_over_stale = false;
    double stale_after_s = 0.0;
};

// A claim nobody can read (empty, garbage, a folder) names no owner: it is not a claim, or,
// on a file system without hard links, its writer died between creating and writing it (a
// claim is otherwise linked into place whole: try_claim). It is judged by the age
// of the file alone: stale when older than stale_after_s, or, with no such age given, than
// this (so that a farm without --claim-timeout does not wait for it for ever).
inline constexpr double kUnreadableClaimAge = 60.0;

// Whether `owner` no longer holds its claim under `policy`, seen from `self` at `self.time`.
bool claim_is_stale(const ClaimOwner& owner, const ClaimOwner& self, const ClaimPolicy& policy);

// Whether an unreadable claim last written at `written` (seconds since the epoch) is stale,
// seen at `now` (see kUnreadableClaimAge).
bool unreadable_claim_is_stale(int64_t written, int64_t now, const ClaimPolicy& policy);

// The claim file of a frame: ".NAME.claim" in the frame's directory (hidden, like the
// atomic writer's temporaries).
std::filesystem::path claim_path(const std::filesystem::path& frame);

// taken_over: claimed after breaking a stale claim (its owner may have left a temporary).
enum class ClaimResult { claimed, taken_over, held };

// Tries to claim `frame`. Throws tessera::Error when the folder cannot take the claim file
// (permissions, full disk), naming it.
ClaimResult try_claim(const std::filesystem::path& frame, const ClaimPolicy& policy);

// Removes this process's claim of `frame` (after the frame is published, or to hand an
// unrendered frame back). A claim that is not ours is left alone.
void release_claim(const std::filesystem::path& frame);

}  // namespace tessera::farm
