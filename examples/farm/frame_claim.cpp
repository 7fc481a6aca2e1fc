#include "examples/farm/frame_claim.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <ctime>
#include <fstream>
#include <sstream>
#include <system_error>

#include "raster/core/error.h"

namespace tessera::farm {

namespace fs = std::filesystem;

std::string ClaimOwner::text() const {
    return host + " " + std::to_string(pid) + " " + std::to_string(time) + "\n";
}

std::optional<ClaimOwner> ClaimOwner::parse(const std::string& text) {
    std::istringstream in(text);
    ClaimOwner o;
    if (!(in >> o.host >> o.pid >> o.time) || o.pid <= 0) return std::nullopt;
    return o;
}

ClaimOwner current_owner() {
    char host[256] = {};
    if (gethostname(host, sizeof host - 1) != 0) std::strcpy(host, "unknown");
    return {host, int64_t(getpid()), int64_t(std::time(nullptr))};
}

bool claim_is_stale(const ClaimOwner& owner, const ClaimOwner& self, const ClaimPolicy& policy) {
    if (!policy.take_over_stale) return false;
    // kill(pid, 0) fails with ESRCH only when no such process exists (EPERM: it exists).
    if (owner.host == self.host && owner.pid != self.pid && kill(pid_t(owner.pid), 0) != 0 && errno == ESRCH)
        return true;
    return policy.stale_after_s > 0.0 && double(self.time - owner.time) > policy.stale_after_s;
}

bool unreadable_claim_is_stale(int64_t written, int64_t now, const ClaimPolicy& policy) {
    if (!policy.take_over_stale) return false;
    return double(now - written) > (policy.stale_after_s > 0.0 ? policy.stale_after_s : kUnreadableClaimAge);
}

fs::path claim_path(const fs::path& frame) {
    std::string name = ".";  // appended piecewise: GCC 12 misreports "." + string (-Wrestrict)
    name += frame.filename().string();
    name += ".claim";
    return frame.parent_path() / name;
}

namespace {

// The whole file, or "" when it is missing or unreadable (a claim being replaced).
std::string read_small_file(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return in ? s.str() : std::string();
}

// A claim as found: its text and when it was last written (0 when it is gone).
struct SeenClaim {
    std::string text;
    int64_t written = 0;
    bool operator==(const SeenClaim&) const = default;
};

SeenClaim look_at(const fs::path& claim) {
    struct stat st {};
    if (::stat(claim.c_str(), &st) != 0) return {};
    return {S_ISREG(st.st_mode) ? read_small_file(claim) : std::string(), int64_t(st.st_mtime)};
}

bool is_stale(const SeenClaim& seen, const ClaimOwner& self, const ClaimPolicy& policy) {
    if (seen.written == 0) return false;  // gone meanwhile: the next create decides
    if (const std::optional<ClaimOwner> owner = ClaimOwner::parse(seen.text))
        return claim_is_stale(*owner, self, policy);
    return unreadable_claim_is_stale(seen.written, self.time, policy);
}

[[noreturn]] void fail(const fs::path& p, const char* what) {
    throw Error("cannot claim frame with '" + p.string() + "': " + what);
}

// Creates `path` with `flags` and writes `text` into it; false when `flags` has O_EXCL and
// the file exists. A failed write removes the file again; other failures throw, naming `claim`.
bool write_new_file(const fs::path& path, int flags, const std::string& text, const fs::path& claim) {
    const int fd = open(path.c_str(), flags | O_CREAT | O_WRONLY | O_CLOEXEC, 0644);
    if (fd < 0) {
        if (errno == EEXIST && (flags & O_EXCL)) return false;
        fail(claim, std::strerror(errno));
    }
    const ssize_t n = write(fd, text.data(), text.size());
    const int write_errno = errno;
    close(fd);
    if (n != ssize_t(text.size())) {
        unlink(path.c_str());
        fail(claim, n < 0 ? std::strerror(write_errno) : "short write");
    }
    return true;
}

// Creates the claim file exclusively, with its text already in it; false when it already
// exists. The text is written to a temporary first and linked into place (link() fails with
// EEXIST like an exclusive create), so a claimer killed at any instant leaves either no claim
// or a whole one naming it, never an empty claim that only its age could break. The
// temporary is named as the atomic writer names a frame's temporaries (".NAME.tmp<pid>_..."),
// so whatever cleans a dead writer's temporaries of the frame cleans this one too.
bool create_claim(const fs::path& frame, const fs::path& claim, const ClaimOwner& self) {
    std::string name = ".";  // appended piecewise: GCC 12 misreports "." + string (-Wrestrict)
    name += frame.filename().string();
    name += ".tmp";
    name += std::to_string(self.pid);
    name += "_claim";
    static std::atomic<unsigned> counter{0};  // unique per call, as the writer's temporaries
    name += std::to_string(counter++);
    const fs::path temporary = frame.parent_path() / name;
    const std::string text = self.text();
    write_new_file(temporary, O_TRUNC, text, claim);
    const int linked = link(temporary.c_str(), claim.c_str());
    const int link_errno = errno;
    unlink(temporary.c_str());
    if (linked == 0) return true;
    if (link_errno == EEXIST) return false;
    // ENOENT: a process that took over this frame's stale claim removed the temporaries of
    // the frame, ours included; the next round tries again.
    if (link_errno == ENOENT) return false;
    if (link_errno != EPERM && link_errno != ENOTSUP && link_errno != EXDEV) fail(claim, std::strerror(link_errno));
    // A file system without hard links: create and write in two steps (a kill between them
    // leaves the empty claim kUnreadableClaimAge describes).
    return write_new_file(claim, O_EXCL, text, claim);
}

}  // namespace

ClaimResult try_claim(const fs::path& frame, const ClaimPolicy& policy) {
    const fs::path claim = claim_path(frame);
    const ClaimOwner self = current_owner();
    // A few rounds: each lost race against another process breaking the same stale claim
    // starts over with a fresh exclusive create.
    for (int round = 0; round < 4; ++round) {
        if (create_claim(frame, claim, self)) return round == 0 ? ClaimResult::claimed : ClaimResult::taken_over;
        const SeenClaim seen = look_at(claim);
        if (seen.written == 0) continue;  // released meanwhile: create again
        if (!is_stale(seen, self, policy)) return ClaimResult::held;
        const fs::path moved = claim.string() + ".stale." + self.host + "." + std::to_string(self.pid);
        if (std::rename(claim.c_str(), moved.c_str()) != 0) {
            if (errno == ENOENT) continue;  // someone else broke it first
            fail(claim, std::strerror(errno));
        }
        std::error_code ignored;
        if (look_at(moved) != seen) {
            // Between reading and renaming, another process broke the stale claim and made
            // its own, which we just moved: give it back (link fails if a third one exists).
            (void)link(moved.c_str(), claim.c_str());
            fs::remove(moved, ignored);
            return ClaimResult::held;
        }
        fs::remove(moved, ignored);  // a file, or an empty folder in the claim's place
    }
    return ClaimResult::held;
}

void release_claim(const fs::path& frame) {
    const fs::path claim = claim_path(frame);
    const std::optional<ClaimOwner> owner = ClaimOwner::parse(read_small_file(claim));
    const ClaimOwner self = current_owner();
    if (owner && owner->host == self.host && owner->pid == self.pid) unlink(claim.c_str());
}

}  // namespace tessera::farm
