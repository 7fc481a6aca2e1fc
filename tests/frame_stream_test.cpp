// FrameStream: bands handed to a background writer one at a time give the file a whole-frame
// write gives; a failed band write is reported by a later call, never lost; an abandoned
// stream leaves nothing. (Run under ThreadSanitizer by `make tsan`.)
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <string>

#include "raster/core/error.h"
#include "raster/io/image_io.h"
#include "raster/output/frame_stream.h"

namespace fs = std::filesystem;
using namespace tessera;

namespace {

fs::path scratch_dir() {
    const fs::path dir = fs::temp_directory_path() / ("tessera_frame_stream_" + std::to_string(getpid()));
    fs::create_directories(dir);
    return dir;
}

Frame pattern(int w, int h) {
    Frame f(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) f.at(x, y) = {float(x % 17) / 16.0f, float(y) / float(h), 0.5f, 1.0f};
    return f;
}

Frame rows_of(const Frame& f, int y0, int y1) {
    Frame band(f.width, y1 - y0);
    std::copy(f.pixels.begin() + ptrdiff_t(y0) * f.width, f.pixels.begin() + ptrdiff_t(y1) * f.width,
              band.pixels.begin());
    return band;
}

}  // namespace

// PNG only: its encoder runs on the calling thread, so ThreadSanitizer sees every thread
// involved. OpenImageIO's EXR reader and writer use its own thread pool, which is not built
// with TSan and is reported as racing with itself; the formats are compared with whole
// writes in ImageStream.BandsMakeTheSameImageAsAWholeWrite.
TEST(FrameStream, BandsGiveTheWholeFramesFile) {
    const fs::path dir = scratch_dir();
    const Frame frame = pattern(96, 200);
    output::FrameStream stream(dir / "f.png", frame.width, frame.height);
    for (int y = 0; y < frame.height; y += 64) stream.write(y, rows_of(frame, y, std::min(frame.height, y + 64)));
    stream.commit();
    output::write_frame(dir / "whole.png", frame);
    EXPECT_EQ(io::read_image(dir / "f.png").pixels, io::read_image(dir / "whole.png").pixels);
    fs::remove_all(dir);
}

TEST(FrameStream, AFailedBandIsReportedByALaterCall) {
    if (!fs::exists("/dev/full")) GTEST_SKIP() << "no /dev/full";
    const fs::path dir = scratch_dir();
    fs::create_symlink("/dev/full", dir / "full.png");
    const Frame frame = pattern(512, 256);
    bool reported = false;
    try {
        output::FrameStream stream(dir / "full.png", frame.width, frame.height);
        for (int y = 0; y < frame.height; y += 64) stream.write(y, rows_of(frame, y, y + 64));
        stream.commit();
    } catch (const Error& e) {
        reported = std::string(e.what()).find("No space left on device") != std::string::npos;
    }
    EXPECT_TRUE(reported);
    fs::remove_all(dir);
}

TEST(FrameStream, AnAbandonedStreamLeavesNothing) {
    const fs::path dir = scratch_dir();
    const Frame frame = pattern(64, 256);
    {
        output::FrameStream stream(dir / "half.png", frame.width, frame.height);
        stream.write(0, rows_of(frame, 0, 128));
    }
    EXPECT_TRUE(fs::is_empty(dir));
    fs::remove_all(dir);
}
