#include "bench/peer/frame_files.h"

#include <bit>
#include <cstring>
#include <string>

#include "raster/atomic_file.h"

namespace tessera::peer {

static_assert(std::endian::native == std::endian::little,
              "TSID and PFM are written as little-endian from memory");

void write_triangle_ids(const std::filesystem::path& path, int width, int height,
                        const std::vector<uint32_t>& ids) {
    const std::string header =
        "TSID " + std::to_string(width) + " " + std::to_string(height) + "\n";
    std::vector<std::byte> bytes(header.size() + ids.size() * 4);
    std::memcpy(bytes.data(), header.data(), header.size());
    std::memcpy(bytes.data() + header.size(), ids.data(), ids.size() * 4);
    write_file_atomically(path, bytes);
}

void write_depth_pfm(const std::filesystem::path& path, int width, int height,
                     const std::vector<float>& depth) {
    const std::string header =
        "Pf\n" + std::to_string(width) + " " + std::to_string(height) + "\n-1.0\n";
    const size_t row = size_t(width) * 4;
    std::vector<std::byte> bytes(header.size() + row * size_t(height));
    std::memcpy(bytes.data(), header.data(), header.size());
    for (int y = 0; y < height; ++y)
        std::memcpy(bytes.data() + header.size() + size_t(height - 1 - y) * row,
                    depth.data() + size_t(y) * size_t(width), row);
    write_file_atomically(path, bytes);
}

}  // namespace tessera::peer
