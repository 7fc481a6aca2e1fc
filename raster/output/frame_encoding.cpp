#include "raster/output/frame_encoding.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <optional>
#include <string>

#include "raster/core/atomic_file.h"
#include "raster/core/color_space.h"
#include "raster/core/error.h"
#include "raster/io/image_io.h"
#include "raster/output/srgb8.h"

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

std::string exr_compression(const std::filesystem::path& path, const FileSettings& settings) {
    return lower_extension(path) == ".exr" ? exr_compression_name(settings.exr) : "";
}

std::vector<uint8_t> encode_srgb8(const Frame& frame) {
    std::vector<uint8_t> out(frame.pixels.size() * 4);
    encode_srgb8(frame.pixels.data(), frame.pixels.size(), out.data());
    return out;
}
std::vector<uint16_t> encode_srgb16(const Frame& frame) { return encode<uint16_t>(frame, 65535.0f); }

io::PixelType frame_pixel_type(const std::filesystem::path& path) {
    const std::string ext = lower_extension(path);
    if (ext == ".exr") return io::PixelType::f32;
    if (ext == ".tif" || ext == ".tiff") return io::PixelType::u16;
    return io::PixelType::u8;
}

bool frame_format_supported(const std::filesystem::path& path) {
    return lower_extension(path) == ".png" || io::image_format_supported(path);
}

Error non_finite_frame_error(const std::filesystem::path& path, size_t pixels) {
    return Error("cannot write '" + path.string() + "': " + std::to_string(pixels) +
                 " pixel(s) came out NaN or infinite (a value of the scene overflows single precision)");
}

OwnedImage encode_frame(const std::filesystem::path& path, const Frame& frame, std::vector<uint8_t> storage) {
    // A frame holding NaN or Inf (a value of the scene that overflowed float, or a bug) is never
    // written: an EXR would carry it on into compositing, 8-bit encodings would hide it as
    // black or white. Finite values are what every renderer stage is meant to produce.
    const auto refuse_non_finite = [&] {
        size_t non_finite = 0;
        for (const glm::vec4& p : frame.pixels)
            non_finite += !(std::isfinite(p.r) && std::isfinite(p.g) && std::isfinite(p.b) && std::isfinite(p.a));
        if (non_finite > 0) throw non_finite_frame_error(path, non_finite);
    };
    OwnedImage image{frame.width, frame.height, 4, frame_pixel_type(path), std::move(storage)};
    const auto keep = [&image](const auto& values) {
        const auto* bytes = reinterpret_cast<const uint8_t*>(values.data());
        image.bytes.assign(bytes, bytes + values.size() * sizeof(values[0]));
    };
    switch (image.type) {
        case io::PixelType::f32:
            refuse_non_finite();
            keep(frame.pixels);
            break;
        case io::PixelType::u16:
            refuse_non_finite();
            keep(encode_srgb16(frame));
            break;
        case io::PixelType::u8:
            // One pass: the encoder reports non-finite values, which are counted only then.
            // One thread: it runs on the background writers, whose synchronisation
            // ThreadSanitizer checks (make tsan); oneTBB's workers would show as races there.
            image.bytes.resize(frame.pixels.size() * 4);  // a recycled buffer keeps its pages
            if (!encode_srgb8(frame.pixels.data(), frame.pixels.size(), image.bytes.data())) refuse_non_finite();
            break;
    }
    return image;
}

void write_encoded(const std::filesystem::path& path, const OwnedImage& image, const FileSettings& settings,
                   PngEncoder* png) {
    if (lower_extension(path) == ".png" && image.type == io::PixelType::u8 && image.width > 0 && image.height > 0) {
        std::optional<PngEncoder> own;
        if (!png) png = &own.emplace(settings.png);
        std::span<const uint8_t> file;
        try {
            file = png->encode(image.bytes.data(), image.width, image.height, image.channels);
        } catch (const std::exception& e) {
            throw Error("cannot write '" + path.string() + "': " + e.what());
        }
        write_file_atomically(path, std::as_bytes(file));
        return;
    }
    io::write_image(path, image.view(), exr_compression(path, settings));
}

void write_frame(const std::filesystem::path& path, const Frame& frame, const FileSettings& settings) {
    write_encoded(path, encode_frame(path, frame), settings);
}

}  // namespace tessera::output
