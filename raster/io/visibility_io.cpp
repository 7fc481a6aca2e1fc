#include "raster/io/visibility_io.h"

#include <bit>
#include <cstring>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "raster/core/atomic_file.h"
#include "raster/core/error.h"
#include "raster/core/input_file.h"

namespace tessera::io {

static_assert(std::endian::native == std::endian::little, "TSID/PFM writers assume little-endian");

void write_tsid(const std::filesystem::path& path, const VisibilityBuffer& v) {
    // Multisampled: every sample, behind a header that says how many (visibility_io.h).
    const bool per_sample = v.samples > 1;
    const AlignedVector<uint32_t>& ids = per_sample ? v.sample_triangle : v.triangle;
    if (ids.size() != size_t(v.width) * size_t(v.height) * size_t(per_sample ? v.samples : 1))
        throw std::invalid_argument("write_tsid: the visibility buffer holds " + std::to_string(ids.size()) +
                                    " ids, not one per " + (per_sample ? "sample" : "pixel"));
    std::string header = "TSID " + std::to_string(v.width) + " " + std::to_string(v.height);
    if (per_sample) header += " " + std::to_string(v.samples);
    header += "\n";
    std::vector<std::byte> bytes(header.size() + ids.size() * sizeof(uint32_t));
    std::memcpy(bytes.data(), header.data(), header.size());
    std::memcpy(bytes.data() + header.size(), ids.data(), ids.size() * sizeof(uint32_t));
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
    int width = 0, height = 0, samples = 1;
    file >> magic >> width >> height;
    if (file.peek() == ' ') {  // multisampled: "TSID W H N", N a count of pipeline/sample_pattern.h
        file >> samples;
        if (samples == 1) samples = 0;  // one sample has the three-field header
    }
    const bool sample_count = samples == 1 || samples == 4 || samples == 8 || samples == 16;
    if (!file || magic != "TSID" || width <= 0 || height <= 0 || !sample_count || file.get() != '\n')
        throw Error("cannot read '" + path.string() + "': not a TSID file");
    // Check the header against the bytes present before allocating: a corrupt header must not
    // ask for gigabytes (found by tests/fuzz/fuzz_image.cpp).
    const std::streampos data_start = file.tellg();
    file.seekg(0, std::ios::end);
    const uint64_t available = uint64_t(file.tellg() - data_start);
    file.seekg(data_start);
    const uint64_t count = uint64_t(width) * uint64_t(height) * uint64_t(samples);
    if (count * sizeof(uint32_t) > available) throw Error("cannot read '" + path.string() + "': truncated");
    VisibilityBuffer v;
    v.reset(width, height);
    AlignedVector<uint32_t>& ids = samples > 1 ? v.sample_triangle : v.triangle;
    v.samples = samples;
    ids.resize(size_t(count));
    file.read(reinterpret_cast<char*>(ids.data()), std::streamsize(ids.size() * sizeof(uint32_t)));
    if (!file) throw Error("cannot read '" + path.string() + "': truncated");
    return v;
}

}  // namespace tessera::io
