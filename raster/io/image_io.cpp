#include "raster/io/image_io.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <cstdint>
#include <string>
#include <system_error>
#include <vector>

#include "raster/core/atomic_file.h"
#include "raster/core/color_space.h"
#include "raster/core/error.h"
#include "raster/core/input_file.h"
#include "raster/io/date_stamp.h"
#include "raster/io/oiio_pixel_type.h"

namespace tessera::io {
namespace fs = std::filesystem;

namespace {

std::string describe(const fs::path& path) { return "'" + path.string() + "'"; }

// The 8-bit sRGB colour channels of `image` decoded to linear light (IEC 61966-2-1), alpha as
// v / 255.
std::vector<float> srgb8_to_linear(const ImageView& image) {
    float decoded[256];
    for (int v = 0; v < 256; ++v) decoded[v] = srgb_to_linear(float(v) / 255.0f);
    const int c = image.channels;
    const int alpha = c == 2 || c == 4 ? c - 1 : -1;
    const auto* in = static_cast<const uint8_t*>(image.pixels);
    std::vector<float> out(size_t(image.width) * size_t(image.height) * size_t(c));
    for (size_t i = 0; i < out.size(); ++i)
        out[i] = int(i % size_t(c)) == alpha ? float(in[i]) / 255.0f : decoded[in[i]];
    return out;
}

}  // namespace

bool image_format_supported(const fs::path& path) {
    auto out = OIIO::ImageOutput::create(path.string());
    if (!out) {
        (void)OIIO::geterror();  // clear the thread's pending message
        return false;
    }
    return true;
}

void write_image(const fs::path& path, const ImageView& image) {
    if (image.width <= 0 || image.height <= 0 || image.channels <= 0 || !image.pixels)
        throw Error("cannot write " + describe(path) + ": the image is empty");

    // Encode in memory, then hand the bytes to write_file_atomically: OpenImageIO's own file
    // writers do not all report a failed fwrite (a full disk gave a "successful" empty PNG).
    std::vector<unsigned char> encoded;
    OIIO::Filesystem::IOVecOutput sink(encoded);
    auto out = OIIO::ImageOutput::create(path.string(), &sink);
    if (!out) {
        std::string why = OIIO::geterror();
        throw Error("cannot write " + describe(path) + ": no image format for extension '" +
                    path.extension().string() + "'" + (why.empty() ? "" : " (" + why + ")"));
    }
    if (!out->supports("ioproxy"))
        throw Error("cannot write " + describe(path) + ": format '" +
                    std::string(out->format_name()) + "' cannot be encoded in memory");

    // OpenEXR and Radiance HDR hold linear light by definition; OpenImageIO would store 8-bit
    // values there as they are (v / 255), which is sRGB-encoded light mislabelled as linear.
    const std::string format = out->format_name();
    const bool decode_srgb = image.srgb && image.type == PixelType::u8 && (format == "openexr" || format == "hdr");
    std::vector<float> linear;
    if (decode_srgb) linear = srgb8_to_linear(image);

    OIIO::ImageSpec spec(image.width, image.height, image.channels,
                         decode_srgb ? OIIO::TypeDesc(OIIO::TypeDesc::HALF) : oiio_type(image.type));
    spec.attribute("DateTime", image_date_time());  // same bytes on every run (date_stamp.h)
    bool ok = out->open(path.string(), spec) &&
              (decode_srgb ? out->write_image(OIIO::TypeDesc::FLOAT, linear.data())
                           : out->write_image(oiio_type(image.type), image.pixels));
    ok = out->close() && ok;
    if (!ok) {
        std::string why = out->geterror();
        throw Error("cannot write " + describe(path) + ": " +
                    (why.empty() ? std::string("encoding failed") : why));
    }
    write_file_atomically(path, std::as_bytes(std::span(encoded.data(), encoded.size())));
}

namespace {

// Colour as the file stores it: PNG (and glTF, which uses it) keeps alpha unassociated, and
// OpenImageIO would otherwise premultiply it on reading, darkening every texel that is not
// fully opaque (an alpha-masked texture's cut-out texels would turn black).
OIIO::ImageSpec straight_alpha() {
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);
    return config;
}

// Decodes what `in` opened; `what` names the source in messages.
FloatImage decode(OIIO::ImageInput& in, const std::string& what) {
    const OIIO::ImageSpec& spec = in.spec();
    // Guard against absurd headers before allocating: a 200-byte file can claim gigapixels
    // (found by fuzz_image), and the float buffer is allocated before decoding starts. 2^28
    // floats (1 GiB) still holds an 8192x8192 RGBA texture.
    const uint64_t count = uint64_t(spec.width) * uint64_t(spec.height) * uint64_t(spec.nchannels);
    if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0 || count > (uint64_t(1) << 28))
        throw Error("cannot read " + what + ": unsupported image size " + std::to_string(spec.width) + "x" +
                    std::to_string(spec.height));
    FloatImage image{spec.width, spec.height, spec.nchannels, std::vector<float>(count)};
    if (!in.read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, image.pixels.data())) {
        std::string why = in.geterror();
        throw Error("cannot read " + what + ": " + (why.empty() ? "decode failed" : why));
    }
    return image;
}

}  // namespace

FloatImage read_image(const fs::path& path) {
    check_input_file(path);  // "no such file", or a device, FIFO or directory refused at once
    const OIIO::ImageSpec config = straight_alpha();
    auto in = OIIO::ImageInput::open(path.string(), &config);
    if (!in) {
        std::string why = OIIO::geterror();
        throw Error("cannot read " + describe(path) + ": " + (why.empty() ? "not an image" : why));
    }
    return decode(*in, describe(path));
}

FloatImage read_image_memory(std::span<const uint8_t> bytes, const std::string& name, const std::string& format) {
    // OpenImageIO reads from memory through an IOProxy; the format is only the first reader
    // tried (each checks the bytes' signature, and the others are tried after it).
    OIIO::Filesystem::IOMemReader memory(bytes.data(), bytes.size());
    const OIIO::ImageSpec config = straight_alpha();
    auto in = OIIO::ImageInput::open("memory." + (format.empty() ? std::string("png") : format), &config, &memory);
    if (!in) {
        std::string why = OIIO::geterror();
        throw Error("cannot read " + name + ": " + (why.empty() ? "not an image" : why));
    }
    return decode(*in, name);
}

}  // namespace tessera::io
