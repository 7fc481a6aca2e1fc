#include "raster/output/frame.h"

#include <algorithm>
#include <cctype>
#include <string>

#include "raster/image_io.h"
#include "raster/output/color_space.h"

namespace tessera {
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

void write_frame(const std::filesystem::path& path, const Frame& frame) {
    const std::string ext = lower_extension(path);
    if (ext == ".exr") {
        write_image(path, {frame.width, frame.height, 4, PixelType::f32, frame.pixels.data()});
    } else if (ext == ".tif" || ext == ".tiff") {
        const std::vector<uint16_t> pixels = encode_srgb16(frame);
        write_image(path, {frame.width, frame.height, 4, PixelType::u16, pixels.data()});
    } else {
        const std::vector<uint8_t> pixels = encode_srgb8(frame);
        write_image(path, {frame.width, frame.height, 4, PixelType::u8, pixels.data()});
    }
}

}  // namespace tessera
