#include "raster/io/visibility_io.h"

#include <bit>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include "raster/core/atomic_file.h"
#include "raster/core/error.h"
#include "raster/core/input_file.h"

namespace tessera::io {

static_assert(std::endian::native == std::endian::little, "TSID/PFM writers assume little-endian");

void write_tsid(const std::filesystem::path& path, const VisibilityBuffer& v) {
    const std::string header = "TSID " + std::to_string(v.width) + " " + std::to_string(v.height) + "\n";
    std::vector<std::byte> bytes(header.size() + v.triangle.size() * sizeof(uint32_t));
    std::memcpy(bytes.data(), header.data(), header.size());
    std::memcpy(bytes.data() + header.size(), v.triangle.data(), v.triangle.size() * sizeof(uint32_t));
    write_file_atomically(path, bytes);
}

void write_depth_pfm(const std::filesystem::path& path, const VisibilityBuffer& v) {
    const std::string header = "Pf\n" + std::to_string(v.width) + " " + std::to_string(v.height) + "\n-1.0\n";
    const size_t row = size_t(v.width) * sizeof(float);
    std::vector<std::byte> bytes(header.size() + row * size_t(v.height));
    std::memcpy(bytes.data(), header.data(), header.size());
    for (int y = 0; y < v.height; ++y)  // PFM rows run bottom to top
        std::memcpy(bytes.data() + header.size() + size_t(v.height - 1 - y) * row,
                    v.depth.data() + size_t(y) * v.width, row);
    write_file_atomically(path, bytes);
}

VisibilityBuffer read_tsid(const std::filesystem::path& path) {
    check_input_file(path);  // a device, FIFO or directory is refused at once
    std::ifstream file(path, std::ios::binary);
    if (!file) throw Error("cannot read '" + path.string() + "': no such file");
    std::string magic;
    int width = 0, height = 0;
    file >> magic >> width >> height;
    if (magic != "TSID" || width <= 0 || height <= 0 || file.get() != '\n')
        throw Error("cannot read '" + path.string() + "': not a TSID file");
    // Check the header against the bytes present before allocating: a corrupt header must not
    // ask for gigabytes (found by tests/fuzz/fuzz_image.cpp).
    const std::streampos data_start = file.tellg();
    file.seekg(0, std::ios::end);
    const uint64_t available = uint64_t(file.tellg() - data_start);
    file.seekg(data_start);
    if (uint64_t(width) * uint64_t(height) * sizeof(uint32_t) > available)
        throw Error("cannot read '" + path.string() + "': truncated");
    VisibilityBuffer v;
    v.reset(width, height);
    file.read(reinterpret_cast<char*>(v.triangle.data()), std::streamsize(v.triangle.size() * sizeof(uint32_t)));
    if (!file) throw Error("cannot read '" + path.string() + "': truncated");
    return v;
}

}  // namespace tessera::io
