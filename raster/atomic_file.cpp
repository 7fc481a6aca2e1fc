#include "raster/atomic_file.h"

#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <string>
#include <system_error>

#include "raster/error.h"

namespace tessera {
namespace fs = std::filesystem;

namespace {

[[noreturn]] void fail(const fs::path& path, const std::string& why) {
    throw Error("cannot write '" + path.string() + "': " + why);
}

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
    const std::string prefix = "." + target.filename().string() + ".tmp";
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

// Writes all bytes to fd; returns 0 or the errno of the first failure.
int write_all(int fd, std::span<const std::byte> bytes) {
    size_t done = 0;
    while (done < bytes.size()) {
        const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
        if (n < 0) {
            if (errno == EINTR) continue;
            return errno;
        }
        if (n == 0) return EIO;
        done += size_t(n);
    }
    return 0;
}

}  // namespace

void write_file_atomically(const fs::path& path, std::span<const std::byte> bytes) {
    std::error_code ec;
    const auto status = fs::status(path, ec);
    if (fs::is_directory(status)) fail(path, "it is a directory");
    const bool in_place = fs::exists(status) && !fs::is_regular_file(status);
    const fs::path parent = path.has_parent_path() ? path.parent_path() : fs::path(".");
    if (!in_place && !fs::is_directory(parent, ec))
        fail(path, "directory '" + parent.string() + "' does not exist");

    if (!in_place) remove_stale_temporaries(path, parent);
    const fs::path written = in_place ? path : temporary_beside(path);
    const int flags = in_place ? O_WRONLY | O_CLOEXEC : O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC;
    const int fd = ::open(written.c_str(), flags, 0644);
    if (fd < 0) fail(path, std::strerror(errno));

    int error = write_all(fd, bytes);
    // fsync before rename: after a crash the name must not point at unwritten blocks. Devices
    // and pipes may refuse fsync (EINVAL), which is not a failure of the write.
    if (error == 0 && ::fsync(fd) != 0 && !(in_place && (errno == EINVAL || errno == EROFS)))
        error = errno;
    if (::close(fd) != 0 && error == 0) error = errno;
    if (error != 0) {
        if (!in_place) fs::remove(written, ec);
        fail(path, std::strerror(error));
    }
    if (!in_place) {
        fs::rename(written, path, ec);
        if (ec) {
            fs::remove(written, ec);
            fail(path, ec.message());
        }
    }
}

}  // namespace tessera
