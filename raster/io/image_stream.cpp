#include "raster/io/image_stream.h"

#include <string>

#include "raster/core/atomic_file.h"
#include "raster/core/error.h"
#include "raster/io/date_stamp.h"
#include "raster/io/image_codec.h"

namespace tessera::io {
namespace fs = std::filesystem;

struct ImageStream::Impl {
    fs::path path;
    AtomicFile file;
    std::string file_failure;  // AtomicFile's message (it names the file), from the encoder's writes
    CodecStream* stream = nullptr;
    int width, height, channels;
    PixelType type;
    bool tiled = false;
    int next_row = 0;

    Impl(const fs::path& p, int w, int h, int c, PixelType t)
        : path(p), file(p), width(w), height(h), channels(c), type(t) {}
    ~Impl() {
        if (stream) image_codec().stream_free(stream);
    }

    // The encoder's writes land in the AtomicFile. A failure is kept and reported after the
    // codec call returns: an exception must not cross the codec and the C libraries under it.
    static bool write_at(void* context, uint64_t offset, const void* bytes, size_t size) {
        Impl& im = *static_cast<Impl*>(context);
        try {
            im.file.write_at(offset, std::span(static_cast<const std::byte*>(bytes), size));
            return true;
        } catch (const Error& e) {
            im.file_failure = e.what();
            return false;
        }
    }
    // After each codec call: the file's own failure first (it says why), then the codec's.
    void check(const std::string& codec_failure) const {
        if (!file_failure.empty()) throw Error(file_failure);
        if (!codec_failure.empty()) throw Error(codec_failure);
    }
    [[noreturn]] void fail(const std::string& why) const {
        throw Error("cannot write '" + path.string() + "': " + why);
    }
};

ImageStream::ImageStream(const fs::path& path, int width, int height, int channels, PixelType type,
                         const std::string& compression) {
    if (width <= 0 || height <= 0 || channels <= 0)
        throw Error("cannot write '" + path.string() + "': the image is empty");
    impl_ = std::make_unique<Impl>(path, width, height, channels, type);
    Impl& im = *impl_;
    const ImageCodec& codec = image_codec();
    // Tiled (kTileRows square) where the format has tiles: EXR, TIFF.
    im.check(codec.stream_open(path.string(), width, height, channels, type, kTileRows, image_date_time(),
                               compression, CodecSink{&im, &Impl::write_at}, &im.stream));
    im.tiled = codec.stream_tiled(im.stream);
}

ImageStream::~ImageStream() = default;

void ImageStream::write_rows(int y, const ImageView& rows) {
    Impl& im = *impl_;
    if (y != im.next_row || rows.width != im.width || rows.channels != im.channels || rows.type != im.type ||
        rows.height <= 0 || y + rows.height > im.height || !rows.pixels)
        im.fail("rows " + std::to_string(y) + ".." + std::to_string(y + rows.height) +
                " do not continue the image where it stopped (row " + std::to_string(im.next_row) + ")");
    if (im.tiled && y + rows.height < im.height && rows.height % kTileRows != 0)
        im.fail("a band of " + std::to_string(rows.height) + " rows does not end on a tile row");
    im.check(image_codec().stream_write(im.stream, y, rows));
    im.next_row = y + rows.height;
}

void ImageStream::commit() {
    Impl& im = *impl_;
    if (im.next_row != im.height)
        im.fail("only " + std::to_string(im.next_row) + " of " + std::to_string(im.height) + " rows were written");
    im.check(image_codec().stream_close(im.stream));
    im.file.commit();
}

}  // namespace tessera::io
