// image_is_complete (raster/io/image_completeness.h), how `render --resume` tells a finished
// frame from a damaged one: a frame written whole is complete; cut short anywhere, it is not;
// a PNG with any one byte changed is not (its chunks' CRCs); a TIFF or EXR with bytes of its
// compressed data changed is not (zlib's Adler-32); nor is a file of another size.
#include "raster/io/image_completeness.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "raster/io/image_io.h"
#include "raster/io/image_stream.h"

namespace tessera::io {
namespace {

namespace fs = std::filesystem;

struct ImageCompleteness : ::testing::TestWithParam<const char*> {
    fs::path dir = fs::temp_directory_path() / ("tessera_completeness_" + std::to_string(getpid()));
    void SetUp() override { fs::create_directories(dir); }
    void TearDown() override { fs::remove_all(dir); }

    // A 24 x 16 RGBA frame of varied pixels (so compressed data is not trivially short).
    fs::path write_frame(const std::string& name) {
        std::vector<uint16_t> pixels(24 * 16 * 4);
        for (size_t i = 0; i < pixels.size(); ++i) pixels[i] = uint16_t(i * 2654435761u >> 16);
        const fs::path path = dir / name;
        write_image(path, ImageView{24, 16, 4, PixelType::u16, pixels.data()});
        return path;
    }
    // Where to cut or change bytes [from, to) of a file: each of the first and last 64 (the
    // header, the last chunk, the end), and every 53rd in between (a few hundred checks per
    // format instead of thousands: the suite also runs under the sanitizers).
    static std::vector<size_t> probes(size_t from, size_t to) {
        std::vector<size_t> at;
        for (size_t i = from; i < to; ++i)
            if (i < from + 64 || i + 64 >= to || (i - from) % 53 == 0) at.push_back(i);
        return at;
    }
    static std::string bytes_of(const fs::path& p) {
        std::ifstream in(p, std::ios::binary);
        return std::string(std::istreambuf_iterator<char>(in), {});
    }
    void put(const fs::path& p, const std::string& bytes) { std::ofstream(p, std::ios::binary) << bytes; }
};

TEST_P(ImageCompleteness, WholeIsCompleteCutShortIsNot) {
    const fs::path path = write_frame(std::string("f.") + GetParam());
    EXPECT_TRUE(image_is_complete(path, 24, 16));
    EXPECT_FALSE(image_is_complete(path, 16, 24)) << "another size";
    EXPECT_FALSE(image_is_complete(dir / "missing.png", 24, 16));
    const std::string whole = bytes_of(path);
    const fs::path cut = dir / (std::string("cut.") + GetParam());
    for (const size_t size : probes(0, whole.size())) {
        put(cut, whole.substr(0, size));
        EXPECT_FALSE(image_is_complete(cut, 24, 16)) << GetParam() << " cut to " << size << " of " << whole.size();
    }
}

TEST_P(ImageCompleteness, ChangedDataIsNotComplete) {
    const fs::path path = write_frame(std::string("f.") + GetParam());
    const std::string whole = bytes_of(path);
    const fs::path changed = dir / (std::string("changed.") + GetParam());
    // PNG: every byte is covered by a CRC or is structure, so any one changed byte is found.
    // TIFF and EXR: the last few hundred bytes hold compressed pixels (the directory and the
    // header come first in what tessera writes), each checked by zlib's Adler-32.
    const bool png = std::string(GetParam()) == "png";
    const size_t from = png ? 0 : whole.size() - std::min<size_t>(whole.size() / 2, 256);
    const size_t to = png ? whole.size() : whole.size() - 16;
    for (const size_t at : probes(from, to)) {
        std::string bytes = whole;
        bytes[at] = char(bytes[at] ^ 0x5a);
        put(changed, bytes);
        EXPECT_FALSE(image_is_complete(changed, 24, 16)) << GetParam() << " changed at byte " << at;
    }
}

INSTANTIATE_TEST_SUITE_P(Formats, ImageCompleteness, ::testing::Values("png", "tif", "exr"));

// A frame streamed band by band (tiled EXR and TIFF, beyond one 8192 pass) is read the same
// way, tile row by tile row.
TEST(ImageCompletenessStreamed, TiledFilesAreReadToTheirEnd) {
    const fs::path dir = fs::temp_directory_path() / ("tessera_completeness_tiled_" + std::to_string(getpid()));
    fs::create_directories(dir);
    for (const char* ext : {"exr", "tif"}) {
        const fs::path path = dir / (std::string("tiled.") + ext);
        std::vector<float> band(100 * 64 * 4, 0.25f);
        ImageStream stream(path, 100, 150, 4, PixelType::f32);
        for (int y = 0; y < 150; y += 64) {
            const int rows = std::min(64, 150 - y);
            stream.write_rows(y, ImageView{100, rows, 4, PixelType::f32, band.data()});
        }
        stream.commit();
        EXPECT_TRUE(image_is_complete(path, 100, 150)) << ext;
        fs::resize_file(path, fs::file_size(path) - 1);
        EXPECT_FALSE(image_is_complete(path, 100, 150)) << ext;
    }
    fs::remove_all(dir);
}

}  // namespace
}  // namespace tessera::io
