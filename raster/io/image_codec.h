// The boundary between tessera and OpenImageIO: the image codec module.
//
// OpenImageIO pulls about 260 shared libraries into a process (OpenCV, GDAL, FFmpeg, DICOM,
// ...), whose symbol lookups cost ~0.6 s of CPU at every start, 30 times what the rest of
// tessera costs, and most runs never need it: frames go out as PNG through tessera's own
// encoder (output/png_encoder.h), scenes are procedural. So every call into OpenImageIO lives
// in one module, raster/io/codec/oiio_codec.cpp, built as a shared object beside the programs
// (libtessera_image_codec.so) and loaded by dlopen on the first read or write of an image that
// needs it. image_io.h, image_stream.h and image_completeness.h are the public face; this
// header is what they share with the module.
//
// Across the boundary go only tessera's plain image types and standard containers (the module
// is built by the same compiler, against the same C++ library); no exception crosses it: each
// entry point returns "" or the complete message (naming the file), which the caller throws as
// tessera::Error. File output stays on tessera's side (AtomicFile, with its clean-up on
// signals): the module encodes into a sink that calls back.
#pragma once
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "raster/io/image_io.h"

namespace tessera::io {

// Where a streamed encoder writes: `write_at` stores `size` bytes at `offset` of the file and
// returns false on failure (the caller keeps the reason).
struct CodecSink {
    void* context = nullptr;
    bool (*write_at)(void* context, uint64_t offset, const void* bytes, size_t size) = nullptr;
};

// A streamed image being encoded into a CodecSink (image_stream.h); owned by the module.
struct CodecStream;

struct ImageCodec {
    // Bumped whenever this struct changes, so a stale module next to a newer program is
    // refused with a message instead of called through the wrong table.
    static constexpr int kAbi = 2;
    int abi = kAbi;

    // The version of OpenImageIO the module runs on.
    std::string (*library_version)();
    // True when there is a writer for the extension of `path`.
    bool (*format_supported)(const std::string& path);
    // `image` encoded as `path`'s extension asks, into `encoded`. `date_time` is the files'
    // DateTime (date_stamp.h); `srgb_to_linear` decodes 8-bit sRGB colour for linear formats;
    // `compression`: the format's compression method by OpenImageIO's name ("zip", "piz",
    // "dwaa", ...), or empty for the format's default.
    std::string (*encode)(const std::string& path, const ImageView& image, const std::string& date_time,
                          float (*srgb_to_linear)(float), const std::string& compression,
                          std::vector<unsigned char>& encoded);
    // A whole image file, or an encoded image in memory (`format`: the extension tried first).
    std::string (*decode_file)(const std::string& path, FloatImage& image);
    std::string (*decode_memory)(std::span<const uint8_t> bytes, const std::string& name,
                                 const std::string& format, FloatImage& image);
    // Streamed writing: open (tiled where the format has tiles, `tile` rows high), rows top to
    // bottom, close. `stream` is set by open whether or not it succeeds, and is freed by
    // stream_free whatever happened.
    std::string (*stream_open)(const std::string& path, int width, int height, int channels, PixelType type,
                               int tile, const std::string& date_time, const std::string& compression,
                               CodecSink sink, CodecStream** stream);
    bool (*stream_tiled)(const CodecStream* stream);
    std::string (*stream_write)(CodecStream* stream, int y, const ImageView& rows);
    std::string (*stream_close)(CodecStream* stream);
    void (*stream_free)(CodecStream* stream);
    // True when every pixel of `path` decodes and the image is width x height.
    bool (*decodes_fully)(const std::string& path, int width, int height);
};

// The module's entry point, looked up by name with dlsym.
#define TESSERA_IMAGE_CODEC_ENTRY "tessera_image_codec"
using ImageCodecEntry = const ImageCodec* (*)();

// The codec, loaded on the first call (thread-safe). The module is the file the environment
// variable TESSERA_IMAGE_CODEC names, or else is looked for next to the running program, then
// where the build put it. Throws tessera::Error saying which files could not be loaded and why.
const ImageCodec& image_codec();

}  // namespace tessera::io
