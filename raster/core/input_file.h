// Files tessera reads (scenes, meshes, textures, camera files), opened so that what is not a
// regular file is refused at once, naming the file: a directory, a device (/dev/zero would
// be read for ever, /dev/urandom is no image), a FIFO or socket (which would block until a
// writer comes). The open never blocks (O_NONBLOCK) and the check is made on the opened file
// (fstat), so a name swapped between the check and the read changes nothing.
#pragma once
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>

namespace tessera {

class InputFile {
public:
    // Throws tessera::Error "cannot read 'PATH': no such file" (or "it is a directory",
    // "not a regular file (a device, FIFO or socket)", "permission denied", ...); `what`
    // ("scene file") is said before the path.
    explicit InputFile(std::filesystem::path path, const std::string& what = "");
    ~InputFile();
    InputFile(const InputFile&) = delete;
    InputFile& operator=(const InputFile&) = delete;

    const std::filesystem::path& path() const { return path_; }
    uint64_t size() const { return size_; }  // at open
    // The next bytes, at most `max` of them (fewer only at the end of the file). Throws
    // tessera::Error on a read error.
    std::string read(size_t max);
    std::string read_rest() { return read(SIZE_MAX); }

private:
    [[noreturn]] void fail(const std::string& why) const;

    std::filesystem::path path_;
    std::string what_;
    int fd_ = -1;
    uint64_t size_ = 0;
};

// Checks that `path` can be opened as a regular file for reading (for readers that open it
// themselves, such as OpenImageIO). Throws tessera::Error as InputFile does.
void check_input_file(const std::filesystem::path& path);

}  // namespace tessera
