#include "raster/io/png_chunks.h"

#include <algorithm>
#include <array>
#include <fstream>

namespace tessera::io {
namespace {

constexpr std::array<uint8_t, 8> kSignature = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};

uint32_t big_endian(const uint8_t* p) {
    return uint32_t(p[0]) << 24 | uint32_t(p[1]) << 16 | uint32_t(p[2]) << 8 | uint32_t(p[3]);
}

// A chunk type as text: its four letters, or hex where a byte is not a letter.
std::string type_name(const uint8_t* type) {
    std::string name;
    for (int i = 0; i < 4; ++i) {
        const char c = char(type[i]);
        const bool letter = (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z');
        if (letter) name += c;
        else {
            static const char* digits = "0123456789abcdef";
            name += "\\x";
            name += digits[type[i] >> 4];
            name += digits[type[i] & 15];
        }
    }
    return name;
}

// Walks the chunks: header(offset, 8 bytes) reads a chunk's length and type into `out`,
// false past the end of the data.
template <class ReadHeader>
std::optional<std::string> walk(uint64_t size, const ReadHeader& header) {
    uint64_t offset = kSignature.size();
    uint8_t h[8];
    while (offset + 8 <= size && header(offset, h)) {
        const uint64_t length = big_endian(h);
        if (length > 0x7FFFFFFFu)  // ISO/IEC 15948 5.3: at most 2^31 - 1
            return "PNG chunk '" + type_name(h + 4) + "' at byte " + std::to_string(offset) + " declares " +
                   std::to_string(length) + " bytes, more than a PNG chunk may hold";
        if (offset + 12 + length > size)
            return "PNG chunk '" + type_name(h + 4) + "' at byte " + std::to_string(offset) + " declares " +
                   std::to_string(length) + " bytes, but the file ends " + std::to_string(size - offset - 8) +
                   " bytes after its header (truncated or damaged)";
        if (h[4] == 'I' && h[5] == 'E' && h[6] == 'N' && h[7] == 'D') break;
        offset += 12 + length;
    }
    return std::nullopt;
}

}  // namespace

std::optional<std::string> png_chunk_problem(std::span<const uint8_t> bytes) {
    if (bytes.size() < kSignature.size() || !std::equal(kSignature.begin(), kSignature.end(), bytes.begin()))
        return std::nullopt;
    return walk(bytes.size(), [&](uint64_t offset, uint8_t* h) {
        std::copy_n(bytes.begin() + std::ptrdiff_t(offset), 8, h);
        return true;
    });
}

std::optional<std::string> png_chunk_problem(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::array<uint8_t, 8> signature{};
    if (!in.read(reinterpret_cast<char*>(signature.data()), signature.size()) || signature != kSignature)
        return std::nullopt;
    std::error_code ec;
    const uint64_t size = std::filesystem::file_size(path, ec);
    if (ec) return std::nullopt;  // the decoder reports what cannot be read
    return walk(size, [&](uint64_t offset, uint8_t* h) {
        in.seekg(std::streamoff(offset));
        return bool(in.read(reinterpret_cast<char*>(h), 8));
    });
}

}  // namespace tessera::io
