#include "raster/core/atomic_file.h"

#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <iterator>
#include <string>
#include <system_error>

#include "raster/core/error.h"

namespace tessera {
namespace fs = std::filesystem;

namespace {

// Unique per process and call, so concurrent writers (threads, or machines sharing a folder
// over NFS) never collide on a temporary. The leading dot keeps it out of frame globs.
fs::path temporary_beside(const fs::path& target) {
    static std::atomic<unsigned> counter{0};
    std::string name = ".";
    name += target.filename().string();
    name += ".tmp";
    name += std::to_string(getpid());
    name += '_';
    name += std::to_string(counter++);
    return target.parent_path() / name;
}

// Removes temporaries of `target` left by writers that were killed (SIGKILL, power loss)
// between creating the temporary and renaming it: ".NAME.tmp<pid>_<n>" whose pid is no
// longer a live process. Rewriting a frame (render --resume) thus also clears what its
// killed predecessor left. Temporaries of live processes are kept: they are being written.
// (A pid names a process on this machine only; two machines writing the same file in a
// shared folder at once is already a conflict, whatever this does.)
void remove_stale_temporaries(const fs::path& target, const fs::path& parent) {
    // Built by appending: GCC 12 warns falsely (-Wrestrict) on "." + string once inlined here.
    std::string prefix = ".";
    prefix += target.filename().string();
    prefix += ".tmp";
    std::error_code ec;
    for (fs::directory_iterator it(parent, ec), end; !ec && it != end; it.increment(ec)) {
        const std::string name = it->path().filename().string();
        if (name.compare(0, prefix.size(), prefix) != 0) continue;
        const char* digits = name.c_str() + prefix.size();
        char* rest = nullptr;
        const long pid = std::strtol(digits, &rest, 10);
        if (rest == digits || *rest != '_' || pid <= 0) continue;
        if (::kill(pid_t(pid), 0) != 0 && errno == ESRCH) {
            std::error_code ignored;
            fs::remove(it->path(), ignored);
        }
    }
}

// The temporaries being written, for remove_unfinished_temporaries() in a signal handler:
// fixed slots (no allocation, no lock), each claimed by its state. A handler unlinks only
// slots whose name is complete (ready); a name it unlinks a moment after its rename finds
// nothing, which is harmless.
struct TemporarySlot {
    enum : int { free = 0, filling = 1, ready = 2 };
    std::atomic<int> state{free};
    char path[4096] = {};
};
TemporarySlot g_temporaries[64];
static_assert(std::atomic<int>::is_always_lock_free, "signal handlers need lock-free atomics");

int register_temporary(const fs::path& path) {
    const std::string& name = path.native();
    if (name.size() >= sizeof(TemporarySlot::path)) return -1;
    for (int i = 0; i < int(std::size(g_temporaries)); ++i) {
        int expected = TemporarySlot::free;
        if (!g_temporaries[i].state.compare_exchange_strong(expected, TemporarySlot::filling)) continue;
        std::memcpy(g_temporaries[i].path, name.c_str(), name.size() + 1);
        g_temporaries[i].state.store(TemporarySlot::ready, std::memory_order_release);
        return i;
    }
    return -1;  // more than 64 at once: this one is not removed on a signal (--resume removes it)
}

void unregister_temporary(int slot) {
    if (slot >= 0) g_temporaries[slot].state.store(TemporarySlot::free, std::memory_order_release);
}

}  // namespace

void remove_unfinished_temporaries() {
    for (TemporarySlot& slot : g_temporaries)
        if (slot.state.load(std::memory_order_acquire) == TemporarySlot::ready) ::unlink(slot.path);
}

AtomicFile::AtomicFile(fs::path path) : path_(std::move(path)) {
    std::error_code ec;
    const auto status = fs::status(path_, ec);
    if (fs::is_directory(status)) fail("it is a directory");
    in_place_ = fs::exists(status) && !fs::is_regular_file(status);
    const fs::path parent = path_.has_parent_path() ? path_.parent_path() : fs::path(".");
    if (!in_place_ && !fs::is_directory(parent, ec)) fail("directory '" + parent.string() + "' does not exist");

    if (!in_place_) remove_stale_temporaries(path_, parent);
    written_ = in_place_ ? path_ : temporary_beside(path_);
    const int flags = in_place_ ? O_WRONLY | O_CLOEXEC : O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC;
    if (!in_place_) slot_ = register_temporary(written_);  // before it exists: a signal never misses it
    fd_ = ::open(written_.c_str(), flags, 0644);
    if (fd_ < 0) fail(std::strerror(errno));
}

AtomicFile::~AtomicFile() {
    if (fd_ >= 0) {
        ::close(fd_);
        std::error_code ignored;
        if (!in_place_) fs::remove(written_, ignored);
    }
    unregister_temporary(slot_);
}

void AtomicFile::fail(const std::string& why) {
    if (fd_ >= 0) {
        ::close(fd_);
        fd_ = -1;
        std::error_code ignored;
        if (!in_place_) fs::remove(written_, ignored);
    }
    unregister_temporary(slot_);
    slot_ = -1;
    throw Error("cannot write '" + path_.string() + "': " + why);
}

void AtomicFile::write_at(uint64_t offset, std::span<const std::byte> bytes) {
    if (fd_ < 0) fail("the file is already closed");
    if (in_place_ && offset != end_) fail("it is not a regular file, and the encoder needs to seek");
    size_t done = 0;
    while (done < bytes.size()) {
        // A regular file takes every write at its offset (the encoder may seek back); a device
        // or pipe only in order.
        const ssize_t n = in_place_ ? ::write(fd_, bytes.data() + done, bytes.size() - done)
                                    : ::pwrite(fd_, bytes.data() + done, bytes.size() - done, off_t(offset + done));
        if (n < 0) {
            if (errno == EINTR) continue;
            fail(std::strerror(errno));
        }
        if (n == 0) fail(std::strerror(EIO));
        done += size_t(n);
    }
    end_ = offset + bytes.size();
}

void AtomicFile::commit() {
    if (fd_ < 0) fail("the file is already closed");
    // fsync before rename: after a crash the name must not point at unwritten blocks. Devices
    // and pipes may refuse fsync (EINVAL), which is not a failure of the write.
    if (::fsync(fd_) != 0 && !(in_place_ && (errno == EINVAL || errno == EROFS))) fail(std::strerror(errno));
    const int fd = fd_;
    fd_ = -1;
    if (::close(fd) != 0) {
        const int error = errno;
        std::error_code ignored;
        if (!in_place_) fs::remove(written_, ignored);
        throw Error("cannot write '" + path_.string() + "': " + std::strerror(error));
    }
    if (in_place_) return;
    std::error_code ec;
    fs::rename(written_, path_, ec);
    unregister_temporary(slot_);
    slot_ = -1;
    if (ec) {
        std::error_code ignored;
        fs::remove(written_, ignored);
        throw Error("cannot write '" + path_.string() + "': " + ec.message());
    }
}

void check_writable(const fs::path& path) {
    const auto fail = [&](const std::string& why) { throw Error("cannot write '" + path.string() + "': " + why); };
    std::error_code ec;
    const auto status = fs::status(path, ec);
    if (fs::is_directory(status)) fail("it is a directory");
    // As AtomicFile: a device or FIFO is written in place, anything else through a temporary
    // beside it, in its folder.
    const bool in_place = fs::exists(status) && !fs::is_regular_file(status);
    const fs::path parent = path.has_parent_path() ? path.parent_path() : fs::path(".");
    if (!in_place && !fs::is_directory(parent, ec)) fail("directory '" + parent.string() + "' does not exist");
    if (::access((in_place ? path : parent).c_str(), W_OK) != 0) fail(std::strerror(errno));
}

void write_file_atomically(const fs::path& path, std::span<const std::byte> bytes) {
    AtomicFile file(path);
    file.write_at(0, bytes);
    file.commit();
}

}  // namespace tessera
