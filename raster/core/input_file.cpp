#include "raster/core/input_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>

#include "raster/core/error.h"

namespace tessera {

InputFile::InputFile(std::filesystem::path path, const std::string& what) : path_(std::move(path)), what_(what) {
    fd_ = ::open(path_.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    if (fd_ < 0) fail(errno == ENOENT ? "no such file" : errno == EACCES ? "permission denied" : std::strerror(errno));
    struct stat st {};
    const bool stated = ::fstat(fd_, &st) == 0;
    const int error = errno;
    if (!stated || !S_ISREG(st.st_mode)) {
        ::close(fd_);
        fd_ = -1;
        fail(!stated                  ? std::strerror(error)
             : S_ISDIR(st.st_mode)    ? "it is a directory"
                                      : "not a regular file (a device, FIFO or socket)");
    }
    size_ = uint64_t(st.st_size);
    // Regular files never block; the flag only kept the open from waiting on a FIFO.
    ::fcntl(fd_, F_SETFL, ::fcntl(fd_, F_GETFL) & ~O_NONBLOCK);
}

void InputFile::fail(const std::string& why) const {
    throw Error("cannot read " + (what_.empty() ? "" : what_ + " ") + "'" + path_.string() + "': " + why);
}

InputFile::~InputFile() {
    if (fd_ >= 0) ::close(fd_);
}

std::string InputFile::read(size_t max) {
    std::string out;
    const uint64_t hint = std::min<uint64_t>(max, size_);
    out.reserve(size_t(std::min<uint64_t>(hint, uint64_t(1) << 30)));
    char buffer[1 << 16];
    while (out.size() < max) {
        const ssize_t n = ::read(fd_, buffer, std::min(sizeof buffer, max - out.size()));
        if (n < 0) {
            if (errno == EINTR) continue;
            fail(std::strerror(errno));
        }
        if (n == 0) break;
        out.append(buffer, size_t(n));
    }
    return out;
}

void check_input_file(const std::filesystem::path& path) { InputFile file(path); }

}  // namespace tessera
