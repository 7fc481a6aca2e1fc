// A PNG's chunk lengths held against the file's size before a decoder reads it.
//
// libpng, inside OpenImageIO, allocates an ancillary chunk's declared length before reading its
// data: a 331-byte file whose tEXt chunk declared 2,053,532,012 bytes made it allocate 2 GB
// (found by fuzz_image). A chunk that reaches past the end of its file cannot be decoded
// anyway, so refusing such a file first rejects nothing a decoder could read, and gives a
// message that says what is wrong. Files that do not start with the PNG signature (ISO/IEC
// 15948 5.2) are not PNGs and pass.
#pragma once
#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string>

namespace tessera::io {

// What is wrong with the chunk lengths of the PNG in `bytes`, or nothing.
std::optional<std::string> png_chunk_problem(std::span<const uint8_t> bytes);
// The same for a file, reading only its chunk headers.
std::optional<std::string> png_chunk_problem(const std::filesystem::path& path);

}  // namespace tessera::io
