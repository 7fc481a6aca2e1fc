// An image file written a band of rows at a time, top to bottom, so that a frame larger than
// memory (a 16K x 16K poster: 4 GiB of float RGBA) never exists whole (band_layout.h).
//
// EXR and TIFF are written tiled (64 x 64 tiles), which also lets viewers and compositors read
// parts of a huge image; other formats (PNG) as scanlines. The bytes go through an AtomicFile
// (atomic_file.h): the file appears under its name only after commit(), complete. Every write
// OpenImageIO's encoder makes is checked by us, since its own file writers do not all report
// a failed write (a full disk once gave a "successful" empty PNG).
#pragma once
#include <filesystem>
#include <memory>

#include "raster/io/image_io.h"

namespace tessera::io {

class ImageStream {
public:
    // Rows of each band must be a multiple of kTileRows, except the last band's.
    static constexpr int kTileRows = 64;

    // Starts `path` (format from its extension). Throws tessera::Error naming the file (no
    // writer for the extension, unwritable directory).
    // `compression`: as write_image's (image_io.h).
    ImageStream(const std::filesystem::path& path, int width, int height, int channels, PixelType type,
                const std::string& compression = "");
    ~ImageStream();  // without commit(): the temporary is removed, nothing appears
    ImageStream(const ImageStream&) = delete;
    ImageStream& operator=(const ImageStream&) = delete;

    // Appends rows [y, y + rows.height): y must be where the previous band ended, and rows as
    // wide as the image, with its channels and type. Throws tessera::Error.
    void write_rows(int y, const ImageView& rows);
    // Finishes the encoding and publishes the file. Throws tessera::Error if any write failed
    // or rows are missing.
    void commit();

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace tessera::io
