// The image codec module (image_codec.h): every call tessera makes into OpenImageIO. Built as
// a shared object loaded on first use, so that a run which reads and writes no image through
// OpenImageIO never loads its ~260 libraries. Nothing here throws across the boundary: each
// entry point returns "" or the complete message.
#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>
#include <OpenImageIO/oiioversion.h>

#include <algorithm>
#include <exception>
#include <mutex>
#include <new>
#include <stdexcept>
#include <string>
#include <vector>

#include "raster/io/image_codec.h"

namespace tessera::io {
namespace {

// A message for the caller, who throws it as tessera::Error; only inside this file.
struct Failure : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// Runs `body` and turns anything it throws into the message returned.
template <class Body>
std::string guarded(Body&& body) {
    try {
        body();
        return "";
    } catch (const Failure& f) {
        return f.what();
    } catch (const std::bad_alloc&) {
        return "out of memory";
    } catch (const std::exception& e) {
        return std::string("OpenImageIO failed: ") + e.what();
    } catch (...) {
        return "OpenImageIO failed";
    }
}

std::string quoted(const std::string& path) { return "'" + path + "'"; }

std::string extension_of(const std::string& path) {
    const size_t slash = path.find_last_of('/'), dot = path.find_last_of('.');
    return dot == std::string::npos || (slash != std::string::npos && dot < slash) ? "" : path.substr(dot);
}

OIIO::TypeDesc oiio_type(PixelType type) {
    switch (type) {
        case PixelType::u8: return OIIO::TypeDesc::UINT8;
        case PixelType::u16: return OIIO::TypeDesc::UINT16;
        case PixelType::f32: return OIIO::TypeDesc::FLOAT;
    }
    return OIIO::TypeDesc::UNKNOWN;
}

// The 8-bit sRGB colour channels of `image` decoded to linear light by `decode`, alpha (the
// 2nd of two or 4th of four channels) as v / 255.
std::vector<float> srgb8_to_linear(const ImageView& image, float (*decode)(float)) {
    float decoded[256];
    for (int v = 0; v < 256; ++v) decoded[v] = decode(float(v) / 255.0f);
    const int c = image.channels;
    const int alpha = c == 2 || c == 4 ? c - 1 : -1;
    const auto* in = static_cast<const uint8_t*>(image.pixels);
    std::vector<float> out(size_t(image.width) * size_t(image.height) * size_t(c));
    for (size_t i = 0; i < out.size(); ++i)
        out[i] = int(i % size_t(c)) == alpha ? float(in[i]) / 255.0f : decoded[in[i]];
    return out;
}

std::string library_version() { return OIIO_VERSION_STRING; }

bool format_supported(const std::string& path) {
    try {
        auto out = OIIO::ImageOutput::create(path);
        if (!out) {
            (void)OIIO::geterror();  // clear the thread's pending message
            return false;
        }
        return true;
    } catch (...) {
        return false;
    }
}

std::string encode(const std::string& path, const ImageView& image, const std::string& date_time,
                   float (*srgb_to_linear)(float), const std::string& compression,
                   std::vector<unsigned char>& encoded) {
    return guarded([&] {
        // Encoded in memory: OpenImageIO's own file writers do not all report a failed fwrite
        // (a full disk gave a "successful" empty PNG); the caller writes the bytes atomically.
        OIIO::Filesystem::IOVecOutput sink(encoded);
        auto out = OIIO::ImageOutput::create(path, &sink);
        if (!out) {
            const std::string why = OIIO::geterror();
            throw Failure("cannot write " + quoted(path) + ": no image format for extension '" + extension_of(path) +
                          "'" + (why.empty() ? "" : " (" + why + ")"));
        }
        if (!out->supports("ioproxy"))
            throw Failure("cannot write " + quoted(path) + ": format '" + std::string(out->format_name()) +
                          "' cannot be encoded in memory");

        // OpenEXR and Radiance HDR hold linear light by definition; OpenImageIO would store
        // 8-bit values there as they are (v / 255), which is sRGB-encoded light mislabelled as
        // linear.
        const std::string format = out->format_name();
        const bool decode_srgb = image.srgb && image.type == PixelType::u8 && (format == "openexr" || format == "hdr");
        std::vector<float> linear;
        if (decode_srgb) linear = srgb8_to_linear(image, srgb_to_linear);

        OIIO::ImageSpec spec(image.width, image.height, image.channels,
                             decode_srgb ? OIIO::TypeDesc(OIIO::TypeDesc::HALF) : oiio_type(image.type));
        spec.attribute("DateTime", date_time);
        if (!compression.empty()) spec.attribute("compression", compression);
        bool ok = out->open(path, spec) && (decode_srgb ? out->write_image(OIIO::TypeDesc::FLOAT, linear.data())
                                                        : out->write_image(oiio_type(image.type), image.pixels));
        ok = out->close() && ok;
        if (!ok) {
            const std::string why = out->geterror();
            throw Failure("cannot write " + quoted(path) + ": " + (why.empty() ? std::string("encoding failed") : why));
        }
    });
}

// Colour as the file stores it: PNG (and glTF, which uses it) keeps alpha unassociated, and
// OpenImageIO would otherwise premultiply it on reading, darkening every texel that is not
// fully opaque (an alpha-masked texture's cut-out texels would turn black).
OIIO::ImageSpec straight_alpha() {
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);
    return config;
}

// Decodes what `in` opened; `what` names the source in messages.
void decode(OIIO::ImageInput& in, const std::string& what, FloatImage& image) {
    const OIIO::ImageSpec& spec = in.spec();
    // Guard against absurd headers before allocating: a 200-byte file can claim gigapixels
    // (found by fuzz_image), and the float buffer is allocated before decoding starts. 2^28
    // floats (1 GiB) still holds an 8192x8192 RGBA texture. A side is held to 2^16 pixels too:
    // OpenImageIO 2.4's read_image converts a chunk of 256 native scanlines at a time, sized
    // by the width alone, so a BMP claiming 83,886,080 x 1 pixels made it allocate 60 GiB
    // (found by fuzz_image).
    constexpr int kMaxSide = 1 << 16;
    const uint64_t count = uint64_t(spec.width) * uint64_t(spec.height) * uint64_t(spec.nchannels);
    if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0 || spec.width > kMaxSide ||
        spec.height > kMaxSide || count > (uint64_t(1) << 28))
        throw Failure("cannot read " + what + ": unsupported image size " + std::to_string(spec.width) + "x" +
                      std::to_string(spec.height));
    image = FloatImage{spec.width, spec.height, spec.nchannels, std::vector<float>(count)};
    if (!in.read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, image.pixels.data())) {
        const std::string why = in.geterror();
        throw Failure("cannot read " + what + ": " + (why.empty() ? "decode failed" : why));
    }
}

std::string decode_file(const std::string& path, FloatImage& image) {
    return guarded([&] {
        const OIIO::ImageSpec config = straight_alpha();
        auto in = OIIO::ImageInput::open(path, &config);
        if (!in) {
            const std::string why = OIIO::geterror();
            throw Failure("cannot read " + quoted(path) + ": " + (why.empty() ? "not an image" : why));
        }
        decode(*in, quoted(path), image);
    });
}

std::string decode_memory(std::span<const uint8_t> bytes, const std::string& name, const std::string& format,
                          FloatImage& image) {
    return guarded([&] {
        // Through an IOProxy; the format is only the first reader tried (each checks the
        // bytes' signature, and the others are tried after it).
        OIIO::Filesystem::IOMemReader memory(bytes.data(), bytes.size());
        const OIIO::ImageSpec config = straight_alpha();
        auto in = OIIO::ImageInput::open("memory." + (format.empty() ? std::string("png") : format), &config, &memory);
        if (!in) {
            const std::string why = OIIO::geterror();
            throw Failure("cannot read " + name + ": " + (why.empty() ? "not an image" : why));
        }
        decode(*in, name, image);
    });
}

// OpenImageIO's encoders write through this proxy into the caller's sink. A failed write is
// recorded and reported after the call that made it: an exception must not cross the C
// libraries (libpng, libtiff) underneath the encoders.
class SinkProxy final : public OIIO::Filesystem::IOProxy {
public:
    SinkProxy(const std::string& path, CodecSink sink) : IOProxy(path, Write), sink_(sink) {}
    const char* proxytype() const override { return "tessera-sink"; }
    size_t write(const void* buf, size_t size) override {
        const size_t done = pwrite(buf, size, m_pos);
        m_pos += int64_t(done);
        return done;
    }
    size_t pwrite(const void* buf, size_t size, int64_t offset) override {
        std::lock_guard lock(mutex_);
        if (failed_ || offset < 0) return 0;
        if (!sink_.write_at(sink_.context, uint64_t(offset), buf, size)) {
            failed_ = true;
            return 0;
        }
        size_ = std::max(size_, size_t(offset) + size);
        return size;
    }
    size_t size() const override { return size_; }
    bool failed() const { return failed_; }

private:
    CodecSink sink_;
    std::mutex mutex_;
    size_t size_ = 0;
    bool failed_ = false;
};

}  // namespace

struct CodecStream {
    std::string path;
    SinkProxy proxy;
    std::unique_ptr<OIIO::ImageOutput> out;
    PixelType type = PixelType::u8;
    int width = 0;
    bool tiled = false;

    CodecStream(const std::string& p, CodecSink sink) : path(p), proxy(p, sink) {}
    // When the sink failed, the caller reports its own reason instead of this one.
    [[noreturn]] void fail(const std::string& why) const {
        throw Failure("cannot write " + quoted(path) + ": " + why);
    }
    std::string oiio_error() const {
        const std::string why = out ? out->geterror() : OIIO::geterror();
        return why.empty() ? "encoding failed" : why;
    }
};

namespace {

std::string stream_open(const std::string& path, int width, int height, int channels, PixelType type, int tile,
                        const std::string& date_time, const std::string& compression, CodecSink sink,
                        CodecStream** stream) {
    *stream = nullptr;
    return guarded([&] {
        *stream = new CodecStream(path, sink);
        CodecStream& s = **stream;
        s.type = type;
        s.width = width;
        s.out = OIIO::ImageOutput::create(path, &s.proxy);
        if (!s.out) s.fail("no image format for extension '" + extension_of(path) + "' (" + s.oiio_error() + ")");
        if (!s.out->supports("ioproxy"))
            s.fail("format '" + std::string(s.out->format_name()) + "' cannot be written through a checked file");
        OIIO::ImageSpec spec(width, height, channels, oiio_type(type));
        spec.attribute("DateTime", date_time);
        if (!compression.empty()) spec.attribute("compression", compression);
        s.tiled = s.out->supports("tiles");
        if (s.tiled) spec.tile_width = spec.tile_height = tile;
        // Classic TIFF addresses 4 GiB; BigTIFF only where it is needed, since older readers
        // lack it.
        const double bytes = double(width) * height * channels * double(pixel_type_bytes(type));
        if (bytes > double(uint64_t(1) << 31)) spec.attribute("tiff:bigtiff", 1);
        if (!s.out->open(path, spec)) s.fail(s.oiio_error());
    });
}

bool stream_tiled(const CodecStream* stream) { return stream->tiled; }

std::string stream_write(CodecStream* stream, int y, const ImageView& rows) {
    return guarded([&] {
        CodecStream& s = *stream;
        const OIIO::TypeDesc type = oiio_type(rows.type);
        const bool ok = s.tiled ? s.out->write_tiles(0, s.width, y, y + rows.height, 0, 1, type, rows.pixels)
                                : s.out->write_scanlines(y, y + rows.height, 0, type, rows.pixels);
        if (!ok || s.proxy.failed()) s.fail(s.oiio_error());
    });
}

std::string stream_close(CodecStream* stream) {
    return guarded([&] {
        CodecStream& s = *stream;
        const bool ok = s.out->close();
        if (!ok || s.proxy.failed()) s.fail(s.oiio_error());
        s.out.reset();
    });
}

void stream_free(CodecStream* stream) { delete stream; }

// Every pixel decoded, a band of about 64 rows at a time (whole tile rows for a tiled file:
// read_tiles needs them), so that a missing or damaged chunk is an error (OpenEXR's zip
// chunks carry zlib's Adler-32) while memory stays at a band.
bool decodes_fully(const std::string& path, int width, int height) {
    try {
        auto in = OIIO::ImageInput::open(path);
        if (!in) {
            (void)OIIO::geterror();
            return false;
        }
        const OIIO::ImageSpec& spec = in->spec();
        if (spec.width != width || spec.height != height || spec.nchannels <= 0) return false;
        const int band = spec.tile_height > 0 ? spec.tile_height * std::max(1, 64 / spec.tile_height) : 64;
        std::vector<float> pixels(size_t(spec.width) * size_t(band) * size_t(spec.nchannels));
        for (int y = 0; y < spec.height; y += band) {
            const int end = std::min(spec.height, y + band);
            const bool ok = spec.tile_width > 0
                                ? in->read_tiles(0, 0, spec.x, spec.x + spec.width, spec.y + y, spec.y + end, 0, 1, 0,
                                                 spec.nchannels, OIIO::TypeDesc::FLOAT, pixels.data())
                                : in->read_scanlines(0, 0, spec.y + y, spec.y + end, 0, 0, spec.nchannels,
                                                     OIIO::TypeDesc::FLOAT, pixels.data());
            if (!ok) {
                (void)in->geterror();
                return false;
            }
        }
        return true;
    } catch (...) {
        return false;
    }
}

const ImageCodec kCodec{
    ImageCodec::kAbi, library_version, format_supported, encode,       decode_file, decode_memory,
    stream_open,      stream_tiled,    stream_write,     stream_close, stream_free, decodes_fully,
};

}  // namespace
}  // namespace tessera::io

extern "C" __attribute__((visibility("default"))) const tessera::io::ImageCodec* tessera_image_codec() {
    return &tessera::io::kCodec;
}
