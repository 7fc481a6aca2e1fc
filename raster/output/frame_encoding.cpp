#include "raster/output/frame_encoding.h"

#include <algorithm>
#include <cctype>
#include <string>

#include "raster/io/image_io.h"
#include "raster/core/color_space.h"

namespace tessera::output {
namespace {

template <class T>
std::vector<T> encode(const Frame& frame, float levels) {
    std::vector<T> out(frame.pixels.size() * 4);
    for (size_t i = 0; i < frame.pixels.size(); ++i) {
        const glm::vec4 p = frame.pixels[i];
        for (int c = 0; c < 3; ++c) out[4 * i + size_t(c)] = T(linear_to_srgb(p[c]) * levels + 0.5f);
        const float a = p.a > 0.0f ? std::min(p.a, 1.0f) : 0.0f;  // NaN -> 0
        out[4 * i + 3] = T(a * levels + 0.5f);
    }
    return out;
}

std::string lower_extension(const std::filesystem::path& path) {
    std::string e = path.extension().string();
    std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return e;
}

}  // namespace

std::vector<uint8_t> encode_srgb8(const Frame& frame) { return encode<uint8_t>(frame, 255.0f); }
std::vector<uint16_t> encode_srgb16(const Frame& frame) { return encode<uint16_t>(frame, 65535.0f); }

io::PixelType frame_pixel_type(const std::filesystem::path& path) {
    const std::string ext = lower_extension(path);
    if (ext == ".exr") return io::PixelType::f32;
    if (ext == ".tif" || ext == ".tiff") return io::PixelType::u16;
    return io::PixelType::u8;
}

OwnedImage encode_frame(const std::filesystem::path& path, const Frame& frame) {
    OwnedImage image{frame.width, frame.height, 4, frame_pixel_type(path), {}};
    const auto keep = [&image](const auto& values) {
        const auto* bytes = reinterpret_cast<const uint8_t*>(values.data());
        image.bytes.assign(bytes, bytes + values.size() * sizeof(values[0]));
    };
    switch (image.type) {
        case io::PixelType::f32: keep(frame.pixels); break;
        case io::PixelType::u16: keep(encode_srgb16(frame)); break;
        case io::PixelType::u8: image.bytes = encode_srgb8(frame); break;
    }
    return image;
}

void write_frame(const std::filesystem::path& path, const Frame& frame) {
    io::write_image(path, encode_frame(path, frame).view());
}

}  // namespace tessera::output
