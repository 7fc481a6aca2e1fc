#include "raster/output/frame_stream.h"

#include <utility>

#include "raster/core/trace.h"

namespace tessera::output {

FrameStream::FrameStream(const std::filesystem::path& path, int width, int height, const FileSettings& settings)
    : path_(path), file_(path, width, height, 4, frame_pixel_type(path), exr_compression(path, settings)) {}

FrameStream::~FrameStream() {
    if (in_flight_.valid()) in_flight_.wait();  // its failure, if any, dies with the file
}

void FrameStream::wait() {
    if (in_flight_.valid()) in_flight_.get();
}

void FrameStream::write(int y, OwnedImage encoded) {
    wait();
    in_flight_ = std::async(std::launch::async, [this, y, encoded = std::move(encoded)] {
        TraceScope trace("write band", "io", y);
        file_.write_rows(y, encoded.view());
    });
}

void FrameStream::commit() {
    wait();
    file_.commit();
}

}  // namespace tessera::output
