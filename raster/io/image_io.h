// Image files through OpenImageIO: PNG, EXR, TIFF (and anything else OIIO writes), chosen by
// the file name's extension. Rows are stored top to bottom, channels interleaved.
//
// Writing is atomic (see atomic_file.h): an interrupted or failed write never leaves a
// half-written image under the final name.
#pragma once
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

namespace tessera::io {

enum class PixelType { u8, u16, f32 };

inline size_t pixel_type_bytes(PixelType type) {
    return type == PixelType::u8 ? 1 : type == PixelType::u16 ? 2 : 4;
}

// A read-only view of pixels in memory; `pixels` holds width*height*channels values of `type`.
// `srgb` says that 8-bit colour channels hold sRGB-encoded display values (a rendered or
// colour-mapped image) rather than data (normals, masks): write_image decodes those to linear
// light for formats that store linear light (OpenEXR, Radiance HDR). Alpha (the 2nd of two or
// 4th of four channels) is linear in every format and never decoded.
struct ImageView {
    int width = 0;
    int height = 0;
    int channels = 0;
    PixelType type = PixelType::u8;
    const void* pixels = nullptr;
    bool srgb = false;
};

// An image read back as 32-bit floats (8/16-bit files are normalised to [0,1]).
struct FloatImage {
    int width = 0;
    int height = 0;
    int channels = 0;
    std::vector<float> pixels;
    float at(int x, int y, int c) const { return pixels[(size_t(y) * width + x) * channels + c]; }
};

// Writes `image` to `path`; the file stores the pixel type given where the format supports it
// (OpenImageIO converts otherwise, e.g. float to 16-bit for PNG), except that 8-bit sRGB
// colour (ImageView::srgb) bound for a linear-light format is stored as linear half floats.
// `compression`: the format's compression method by OpenImageIO's name (OpenEXR: "none",
// "zip", "piz", "dwaa", ...), empty for the format's default. Throws tessera::Error.
void write_image(const std::filesystem::path& path, const ImageView& image, const std::string& compression = "");

// Reads any image OpenImageIO understands. Throws tessera::Error with the reason.
FloatImage read_image(const std::filesystem::path& path);

// The same from an encoded file in memory (an image stored inside a model file); `name` is
// used in messages, `format` (a file extension without the dot: "png", "jpg") is the reader
// tried first.
FloatImage read_image_memory(std::span<const uint8_t> bytes, const std::string& name, const std::string& format);

// True when OpenImageIO has a writer for the extension of `path` (".png", ".exr", ...).
bool image_format_supported(const std::filesystem::path& path);

}  // namespace tessera::io
