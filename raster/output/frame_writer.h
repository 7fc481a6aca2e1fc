// Writes frames on a background thread while the next frame renders. Memory stays bounded:
// submit() blocks while `max_pending` frames are still being encoded and written, so a slow
// disk slows the render instead of piling frames up. A write that failed is rethrown (as
// tessera::Error) by the next submit() or by finish(), so no failure goes unreported.
#pragma once
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <exception>
#include <filesystem>
#include <mutex>
#include <thread>
#include <vector>

#include "raster/io/image_io.h"
#include "raster/output/exr_compression.h"
#include "raster/output/png_encoder.h"

namespace tessera::output {

// How the files are compressed (frame_encoding.h's write_encoded).
struct FileSettings {
    PngSettings png;
    ExrCompression exr = ExrCompression::zip;
};

// Pixels the writer owns while the renderer moves on to the next frame.
struct OwnedImage {
    int width = 0;
    int height = 0;
    int channels = 0;
    io::PixelType type = io::PixelType::u8;
    std::vector<uint8_t> bytes;
    io::ImageView view() const { return {width, height, channels, type, bytes.data()}; }
};

class FrameWriter {
public:
    explicit FrameWriter(size_t max_pending = 1, const FileSettings& settings = {});
    ~FrameWriter();  // finishes queued writes; errors are dropped here (call finish() to see them)
    FrameWriter(const FrameWriter&) = delete;
    FrameWriter& operator=(const FrameWriter&) = delete;

    void submit(std::filesystem::path path, OwnedImage image);
    // Waits until every submitted frame is on disk; rethrows the first failure.
    void finish();
    // Paths written so far, in completion order.
    std::vector<std::filesystem::path> written() const;
    // Adds a frame the caller wrote itself (streamed band by band, image_stream.h), so that
    // written() stays the one list of finished frames.
    void record_written(std::filesystem::path path);
    // The pixel buffer of a frame already written, to encode the next one into (encode_frame):
    // its pages stay mapped from frame to frame. Empty when none is free.
    std::vector<uint8_t> spare_bytes();

private:
    struct Job {
        std::filesystem::path path;
        OwnedImage image;
    };
    void run();
    void rethrow_failure_locked();

    const size_t max_pending_;
    const FileSettings settings_;
    PngEncoder png_;  // the worker's, its buffers kept from frame to frame
    mutable std::mutex mutex_;
    std::condition_variable changed_;
    std::deque<Job> queue_;
    size_t in_flight_ = 0;
    bool stopping_ = false;
    std::exception_ptr failure_;
    std::vector<std::filesystem::path> written_;
    std::vector<std::vector<uint8_t>> spare_;  // buffers of written frames, at most max_pending_ + 1
    std::thread worker_;
};

}  // namespace tessera::output
