// Writing whole files so that a reader never sees a half-written one.
//
// The bytes go to a temporary beside the target (same directory, so the same file system),
// every write() is checked (a full disk fails here, not silently), the file is fsync'ed, and
// only then renamed over the target: POSIX rename is atomic, so the target is either the old
// file, absent, or complete. Targets that exist and are not regular files (/dev/stdout,
// /dev/full, a FIFO) are written in place, since a rename would replace the device node.
#pragma once
#include <cstddef>
#include <filesystem>
#include <span>
#include <string_view>

namespace tessera {

// Throws tessera::Error ("cannot write 'PATH': REASON") and leaves no temporary behind.
void write_file_atomically(const std::filesystem::path& path, std::span<const std::byte> bytes);

inline void write_file_atomically(const std::filesystem::path& path, std::string_view text) {
    write_file_atomically(path, std::as_bytes(std::span(text.data(), text.size())));
}

}  // namespace tessera
