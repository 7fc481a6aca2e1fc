#include "raster/output/frame_writer.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "raster/core/error.h"
#include "raster/io/image_completeness.h"

namespace fs = std::filesystem;
using namespace tessera;

namespace {
output::OwnedImage gray(int w, int h, uint8_t value) {
    return {w, h, 3, io::PixelType::u8, std::vector<uint8_t>(size_t(w) * h * 3, value)};
}
}  // namespace

TEST(FrameWriter, WritesEveryFrameInTheBackground) {
    const fs::path dir = fs::temp_directory_path() / "tessera_frame_writer";
    fs::remove_all(dir);
    fs::create_directories(dir);
    output::FrameWriter writer(2);
    for (int f = 0; f < 6; ++f)
        writer.submit(dir / ("f" + std::to_string(f) + ".png"), gray(16, 8, uint8_t(f * 40)));
    writer.finish();
    EXPECT_EQ(writer.written().size(), 6u);
    for (int f = 0; f < 6; ++f) {
        const fs::path p = dir / ("f" + std::to_string(f) + ".png");
        EXPECT_TRUE(io::image_is_complete(p, 16, 8)) << p;
        EXPECT_FALSE(io::image_is_complete(p, 8, 16)) << "wrong size must not count as complete";
        EXPECT_NEAR(io::read_image(p).at(3, 3, 0) * 255.0f, f * 40, 0.5f);
    }
}

TEST(FrameWriter, AFailedWriteIsReportedNotLost) {
    output::FrameWriter writer(1);
    writer.submit("/nonexistent-dir/f.png", gray(4, 4, 0));
    EXPECT_THROW(
        {
            writer.submit("/nonexistent-dir/g.png", gray(4, 4, 0));
            writer.finish();
        },
        Error);
}
