// A frame written band by band (band_layout.h) into its file: each band is encoded for the
// file (frame.h: sRGB 8/16-bit or float) by the caller, then compressed and written by
// ImageStream on a background thread while the caller renders the next band. At most one
// band is in flight, so memory stays two bands; a failed write is rethrown by the next
// write() or by commit(), so none goes unreported.
#pragma once
#include <filesystem>
#include <future>

#include "raster/io/image_stream.h"
#include "raster/output/frame_encoding.h"

namespace tessera::output {

class FrameStream {
public:
    // Throws tessera::Error (as ImageStream). `settings`: the EXR compression (PNG bands are
    // streamed as scanlines by OpenImageIO).
    FrameStream(const std::filesystem::path& path, int width, int height, const FileSettings& settings = {});
    ~FrameStream();  // waits for the band in flight; without commit() the file never appears
    FrameStream(const FrameStream&) = delete;
    FrameStream& operator=(const FrameStream&) = delete;

    // Rows [y, y + band.height), continuing where the previous band ended. Throws
    // tessera::Error for this or the previous band.
    void write(int y, const Frame& band) { write(y, encode_frame(path_, band)); }
    // The same for a band already encoded for this file (encode_frame; e.g. by an MPI rank).
    void write(int y, OwnedImage encoded);
    // Waits for the last band and publishes the file. Throws tessera::Error.
    void commit();

private:
    void wait();

    std::filesystem::path path_;
    io::ImageStream file_;
    std::future<void> in_flight_;
};

}  // namespace tessera::output
