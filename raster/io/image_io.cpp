#include "raster/io/image_io.h"

#include <optional>
#include <string>
#include <vector>

#include "raster/core/atomic_file.h"
#include "raster/core/color_space.h"
#include "raster/core/error.h"
#include "raster/core/input_file.h"
#include "raster/io/date_stamp.h"
#include "raster/io/image_codec.h"
#include "raster/io/png_chunks.h"

namespace tessera::io {
namespace fs = std::filesystem;

namespace {

void check(const std::string& failure) {
    if (!failure.empty()) throw Error(failure);
}

float decode_srgb(float encoded) { return srgb_to_linear(encoded); }

}  // namespace

bool image_format_supported(const fs::path& path) { return image_codec().format_supported(path.string()); }

void write_image(const fs::path& path, const ImageView& image, const std::string& compression) {
    if (image.width <= 0 || image.height <= 0 || image.channels <= 0 || !image.pixels)
        throw Error("cannot write '" + path.string() + "': the image is empty");
    // Encoded in memory, then written atomically: a failed write never leaves a part.
    std::vector<unsigned char> encoded;
    check(image_codec().encode(path.string(), image, image_date_time(), decode_srgb, compression, encoded));
    write_file_atomically(path, std::as_bytes(std::span(encoded.data(), encoded.size())));
}

FloatImage read_image(const fs::path& path) {
    check_input_file(path);  // "no such file", or a device, FIFO or directory refused at once
    if (const std::optional<std::string> problem = png_chunk_problem(path)) throw Error(path.string() + ": " + *problem);
    FloatImage image;
    check(image_codec().decode_file(path.string(), image));
    return image;
}

FloatImage read_image_memory(std::span<const uint8_t> bytes, const std::string& name, const std::string& format) {
    if (const std::optional<std::string> problem = png_chunk_problem(bytes)) throw Error(name + ": " + *problem);
    FloatImage image;
    check(image_codec().decode_memory(bytes, name, format, image));
    return image;
}

}  // namespace tessera::io
