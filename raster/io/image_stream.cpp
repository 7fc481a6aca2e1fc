#include "raster/io/image_stream.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <mutex>
#include <string>

#include "raster/core/atomic_file.h"
#include "raster/core/error.h"
#include "raster/io/date_stamp.h"
#include "raster/io/oiio_pixel_type.h"

namespace tessera::io {
namespace fs = std::filesystem;

namespace {

// OpenImageIO's encoders write through this proxy into the AtomicFile. A failed write is
// recorded and reported after close(): an exception must not cross the C libraries (libpng,
// libtiff) underneath the encoders.
class CheckedFileProxy final : public OIIO::Filesystem::IOProxy {
public:
    explicit CheckedFileProxy(AtomicFile& file) : IOProxy(file.path().string(), Write), file_(file) {}
    const char* proxytype() const override { return "tessera-atomic-file"; }
    size_t write(const void* buf, size_t size) override {
        const size_t done = pwrite(buf, size, m_pos);
        m_pos += int64_t(done);
        return done;
    }
    size_t pwrite(const void* buf, size_t size, int64_t offset) override {
        std::lock_guard lock(mutex_);
        if (!failure_.empty() || offset < 0) return 0;
        try {
            file_.write_at(uint64_t(offset), std::span(static_cast<const std::byte*>(buf), size));
        } catch (const Error& e) {
            failure_ = e.what();
            return 0;
        }
        size_ = std::max(size_, size_t(offset) + size);
        return size;
    }
    size_t size() const override { return size_; }
    const std::string& failure() const { return failure_; }

private:
    AtomicFile& file_;
    std::mutex mutex_;
    size_t size_ = 0;
    std::string failure_;  // AtomicFile's message, which names the file
};

}  // namespace

struct ImageStream::Impl {
    fs::path path;
    AtomicFile file;
    CheckedFileProxy proxy;
    std::unique_ptr<OIIO::ImageOutput> out;
    int width, height, channels;
    PixelType type;
    bool tiled = false;
    int next_row = 0;

    Impl(const fs::path& p, int w, int h, int c, PixelType t)
        : path(p), file(p), proxy(file), width(w), height(h), channels(c), type(t) {}

    [[noreturn]] void fail(const std::string& why) const {
        throw Error(!proxy.failure().empty() ? proxy.failure() : "cannot write '" + path.string() + "': " + why);
    }
    std::string oiio_error() const {
        const std::string why = out ? out->geterror() : OIIO::geterror();
        return why.empty() ? "encoding failed" : why;
    }
};

ImageStream::ImageStream(const fs::path& path, int width, int height, int channels, PixelType type) {
    if (width <= 0 || height <= 0 || channels <= 0)
        throw Error("cannot write '" + path.string() + "': the image is empty");
    impl_ = std::make_unique<Impl>(path, width, height, channels, type);
    Impl& im = *impl_;
    im.out = OIIO::ImageOutput::create(path.string(), &im.proxy);
    if (!im.out) im.fail("no image format for extension '" + path.extension().string() + "' (" + im.oiio_error() + ")");
    if (!im.out->supports("ioproxy"))
        im.fail("format '" + std::string(im.out->format_name()) + "' cannot be written through a checked file");
    OIIO::ImageSpec spec(width, height, channels, oiio_type(type));
    spec.attribute("DateTime", image_date_time());  // same bytes on every run (date_stamp.h)
    im.tiled = im.out->supports("tiles");
    if (im.tiled) spec.tile_width = spec.tile_height = kTileRows;
    // Classic TIFF addresses 4 GiB; BigTIFF only where it is needed, since older readers lack it.
    const double bytes = double(width) * height * channels * double(pixel_type_bytes(type));
    if (bytes > double(uint64_t(1) << 31)) spec.attribute("tiff:bigtiff", 1);
    if (!im.out->open(path.string(), spec)) im.fail(im.oiio_error());
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
    const OIIO::TypeDesc type = oiio_type(rows.type);
    const bool ok = im.tiled ? im.out->write_tiles(0, im.width, y, y + rows.height, 0, 1, type, rows.pixels)
                             : im.out->write_scanlines(y, y + rows.height, 0, type, rows.pixels);
    if (!ok || !im.proxy.failure().empty()) im.fail(im.oiio_error());
    im.next_row = y + rows.height;
}

void ImageStream::commit() {
    Impl& im = *impl_;
    if (im.next_row != im.height)
        im.fail("only " + std::to_string(im.next_row) + " of " + std::to_string(im.height) + " rows were written");
    const bool ok = im.out->close();
    if (!ok || !im.proxy.failure().empty()) im.fail(im.oiio_error());
    im.out.reset();
    im.file.commit();
}

}  // namespace tessera::io
