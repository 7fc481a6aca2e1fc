// Writing whole files so that a reader never sees a half-written one.
//
// The bytes go to a temporary beside the target (same directory, so the same file system),
// every write() is checked (a full disk fails here, not silently), the file is fsync'ed, and
// only then renamed over the target: POSIX rename is atomic, so the target is either the old
// file, absent, or complete. Targets that exist and are not regular files (/dev/stdout,
// /dev/full, a FIFO) are written in place, since a rename would replace the device node.
//
// AtomicFile is the same protocol for a file written piece by piece (a frame streamed band
// by band, whose encoder seeks back to fill in tile offsets): pieces go to the temporary,
// and commit() publishes it. Destroyed without commit(), it removes the temporary.
#pragma once
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <span>
#include <string_view>

namespace tessera {

class AtomicFile {
public:
    // Creates the temporary (or opens the device). Throws tessera::Error naming `path`.
    explicit AtomicFile(std::filesystem::path path);
    ~AtomicFile();
    AtomicFile(const AtomicFile&) = delete;
    AtomicFile& operator=(const AtomicFile&) = delete;

    // Writes `bytes` at byte `offset`. Devices and pipes are written in order only, so there
    // the offset must be where the previous write ended. Throws tessera::Error.
    void write_at(uint64_t offset, std::span<const std::byte> bytes);
    // fsync, close and rename over the target. Throws tessera::Error (the temporary is gone).
    void commit();

    const std::filesystem::path& path() const { return path_; }

private:
    [[noreturn]] void fail(const std::string& why);

    std::filesystem::path path_;     // the target
    std::filesystem::path written_;  // the temporary, or the target itself for a device
    int slot_ = -1;                  // in the table of remove_unfinished_temporaries()
    bool in_place_ = false;
    int fd_ = -1;
    uint64_t end_ = 0;  // where the last write ended (devices: the only offset accepted)
};

// Removes the temporaries of every AtomicFile now open in this process, for a handler of a
// signal that ends it (SIGTERM while a frame is written must not leave the temporary behind).
// Async-signal-safe: unlink(2) on names kept ready in a fixed table (up to 64 open at once).
void remove_unfinished_temporaries();

// Throws the tessera::Error that writing `path` would ("cannot write 'PATH': REASON": a
// directory in the way, a missing or read-only folder), for a command to check its outputs
// before the work that produces them. Writes nothing.
void check_writable(const std::filesystem::path& path);

// Throws tessera::Error ("cannot write 'PATH': REASON") and leaves no temporary behind.
void write_file_atomically(const std::filesystem::path& path, std::span<const std::byte> bytes);

inline void write_file_atomically(const std::filesystem::path& path, std::string_view text) {
    write_file_atomically(path, std::as_bytes(std::span(text.data(), text.size())));
}

}  // namespace tessera
