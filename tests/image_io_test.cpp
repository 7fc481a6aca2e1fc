#include "raster/io/image_io.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <string>
#include <vector>

#include "raster/core/color_space.h"
#include "raster/core/error.h"
#include "raster/io/png_chunks.h"

namespace fs = std::filesystem;
using namespace tessera;

namespace {

fs::path scratch(const char* name) {
    fs::path dir = fs::temp_directory_path() / "tessera_image_io_test";
    fs::create_directories(dir);
    return dir / name;
}

std::vector<uint8_t> file_bytes(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), {}};
}

void overwrite(const fs::path& path, const std::vector<uint8_t>& bytes) {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
}

size_t files_in(const fs::path& dir) {
    return size_t(std::distance(fs::directory_iterator(dir), fs::directory_iterator()));
}

}  // namespace

TEST(ImageIO, PngRoundTripIsExact) {
    const int w = 7, h = 5;
    std::vector<uint8_t> pixels(w * h * 3);
    for (size_t i = 0; i < pixels.size(); ++i) pixels[i] = uint8_t(i * 37);
    const fs::path path = scratch("round.png");
    io::write_image(path, {w, h, 3, io::PixelType::u8, pixels.data()});
    io::FloatImage back = io::read_image(path);
    ASSERT_EQ(back.width, w);
    ASSERT_EQ(back.height, h);
    ASSERT_EQ(back.channels, 3);
    for (size_t i = 0; i < pixels.size(); ++i)
        EXPECT_EQ(int(back.pixels[i] * 255.0f + 0.5f), int(pixels[i])) << "value " << i;
}

// A chunk that declares more bytes than its file holds is refused, naming the chunk, before
// the decoder allocates what it declares (libpng allocated 2 GB for such a tEXt chunk), from a
// file and from memory; the intact file still reads.
TEST(ImageIO, PngChunkLongerThanTheFileIsRefusedFirst) {
    const int w = 4, h = 3;
    std::vector<uint8_t> pixels(w * h * 3, 100);
    const fs::path path = scratch("chunks.png");
    io::write_image(path, {w, h, 3, io::PixelType::u8, pixels.data()});
    std::vector<uint8_t> bytes = file_bytes(path);
    ASSERT_GT(bytes.size(), 33u);
    EXPECT_FALSE(io::png_chunk_problem(bytes));
    EXPECT_NO_THROW(io::read_image(path));
    // IHDR's length (bytes 8-11) set to 0x7A66696C, as the fuzzer's file had for its tEXt.
    std::vector<uint8_t> damaged = bytes;
    damaged[8] = 0x7A, damaged[9] = 0x66, damaged[10] = 0x69, damaged[11] = 0x6C;
    const std::optional<std::string> problem = io::png_chunk_problem(damaged);
    ASSERT_TRUE(problem);
    EXPECT_NE(problem->find("'IHDR' at byte 8 declares 2053532012 bytes"), std::string::npos) << *problem;
    overwrite(path, damaged);
    try {
        io::read_image(path);
        FAIL() << "a damaged PNG was read";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("declares 2053532012 bytes"), std::string::npos) << e.what();
    }
    EXPECT_THROW(io::read_image_memory(damaged, "embedded.png", "png"), Error);
    // Over 2^31 - 1, the largest length a chunk may declare.
    damaged[8] = 0x80;
    EXPECT_NE(io::png_chunk_problem(damaged)->find("more than a PNG chunk may hold"), std::string::npos);
    // Not a PNG: nothing to say.
    damaged[1] = 'Q';
    EXPECT_FALSE(io::png_chunk_problem(damaged));
}

// A header claiming a side over 2^16 pixels is refused before decoding, even when the whole
// image would be small enough: OpenImageIO sizes its conversion buffer by 256 scanlines of
// the claimed width (a BMP claiming 83,886,080 x 1 made it allocate 60 GiB).
TEST(ImageIO, SideLongerThan65536IsRefusedFirst) {
    const int w = 4, h = 1;
    std::vector<uint8_t> pixels(w * h * 3, 100);
    const fs::path path = scratch("wide.bmp");
    io::write_image(path, {w, h, 3, io::PixelType::u8, pixels.data()});
    EXPECT_NO_THROW(io::read_image(path));
    std::vector<uint8_t> bytes = file_bytes(path);
    ASSERT_GT(bytes.size(), 26u);
    ASSERT_EQ(bytes[0], 'B');
    ASSERT_EQ(bytes[1], 'M');
    // BITMAPINFOHEADER width, little-endian at byte 18: 83,886,080 (0x05000000).
    bytes[18] = 0x00, bytes[19] = 0x00, bytes[20] = 0x00, bytes[21] = 0x05;
    overwrite(path, bytes);
    try {
        io::read_image(path);
        FAIL() << "a BMP 83886080 pixels wide was read";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("unsupported image size 83886080x1"), std::string::npos) << e.what();
    }
}

TEST(ImageIO, ExrKeepsFloats) {
    std::vector<float> pixels = {0.0f, 0.25f, 1.5f, 1e4f};
    const fs::path path = scratch("round.exr");
    io::write_image(path, {2, 2, 1, io::PixelType::f32, pixels.data()});
    io::FloatImage back = io::read_image(path);
    ASSERT_EQ(back.pixels.size(), pixels.size());
    for (size_t i = 0; i < pixels.size(); ++i) EXPECT_FLOAT_EQ(back.pixels[i], pixels[i]);
}

// 8-bit sRGB colour written to EXR is stored as linear light: reading it back gives
// srgb_to_linear of each colour value (to half precision), alpha as v / 255; a PNG and a TIFF
// keep the encoded values; 8-bit data that is not sRGB (srgb = false) is stored as v / 255.
TEST(ImageIO, SrgbColourIsDecodedToLinearForExrOnly) {
    std::vector<uint8_t> pixels(256 * 4);
    for (int v = 0; v < 256; ++v)
        for (int c = 0; c < 4; ++c) pixels[size_t(v) * 4 + size_t(c)] = uint8_t(c == 3 ? 255 - v : v);
    io::write_image(scratch("srgb.exr"), {16, 16, 4, io::PixelType::u8, pixels.data(), /*srgb=*/true});
    const io::FloatImage exr = io::read_image(scratch("srgb.exr"));
    ASSERT_EQ(exr.channels, 4);
    for (int v = 0; v < 256; ++v) {
        const float linear = srgb_to_linear(float(v) / 255.0f);
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(exr.pixels[size_t(v) * 4 + size_t(c)], linear, linear * 1e-3f + 1e-7f) << "value " << v;
        EXPECT_NEAR(exr.pixels[size_t(v) * 4 + 3], float(255 - v) / 255.0f, 1e-3f) << "alpha " << v;
    }
    // (RGB here: OpenImageIO's PNG writer would divide colour by an alpha below one.)
    std::vector<uint8_t> rgb(256 * 3);
    for (size_t i = 0; i < rgb.size(); ++i) rgb[i] = uint8_t(i / 3);
    for (const char* name : {"srgb.png", "srgb.tif"}) {
        io::write_image(scratch(name), {16, 16, 3, io::PixelType::u8, rgb.data(), /*srgb=*/true});
        const io::FloatImage back = io::read_image(scratch(name));
        for (size_t i = 0; i < rgb.size(); ++i)
            ASSERT_EQ(int(back.pixels[i] * 255.0f + 0.5f), int(rgb[i])) << name << " value " << i;
    }
    io::write_image(scratch("data.exr"), {16, 16, 4, io::PixelType::u8, pixels.data()});
    const io::FloatImage data = io::read_image(scratch("data.exr"));
    for (size_t i = 0; i < pixels.size(); ++i)
        ASSERT_NEAR(data.pixels[i], float(pixels[i]) / 255.0f, 1e-3f) << "value " << i;
}

TEST(ImageIO, MissingDirectoryIsAnErrorAndLeavesNothing) {
    std::vector<uint8_t> pixel(3, 0);
    EXPECT_THROW(io::write_image(scratch("no/such/dir/x.png"), {1, 1, 3, io::PixelType::u8, pixel.data()}),
                 Error);
}

TEST(ImageIO, UnknownExtensionIsAnError) {
    std::vector<uint8_t> pixel(3, 0);
    EXPECT_THROW(io::write_image(scratch("x.notaformat"), {1, 1, 3, io::PixelType::u8, pixel.data()}),
                 Error);
}

TEST(ImageIO, FullDeviceIsAnErrorNotACrash) {
    if (!fs::exists("/dev/full")) GTEST_SKIP() << "no /dev/full";
    // A ".png" name for the full device: not a regular file, so it is written in place (a
    // rename would replace the device) and the failed write must surface as an Error.
    const fs::path link = scratch("full.png");
    fs::remove(link);
    fs::create_symlink("/dev/full", link);
    std::vector<uint8_t> pixels(64 * 64 * 3, 128);
    EXPECT_THROW(io::write_image(link, {64, 64, 3, io::PixelType::u8, pixels.data()}), Error);
    EXPECT_TRUE(fs::is_character_file("/dev/full"));
}

TEST(ImageIO, FailedWriteLeavesNoTemporary) {
    const fs::path dir = scratch("atomic");
    fs::remove_all(dir);
    fs::create_directories(dir);
    std::vector<uint8_t> pixels(4 * 4 * 3, 9);
    io::write_image(dir / "ok.png", {4, 4, 3, io::PixelType::u8, pixels.data()});
    EXPECT_EQ(files_in(dir), 1u);  // the temporary was renamed, not left beside it
    EXPECT_THROW(io::write_image(dir / "bad.png", {0, 4, 3, io::PixelType::u8, pixels.data()}), Error);
    EXPECT_EQ(files_in(dir), 1u);
}

TEST(ImageIO, ReadingGarbageIsAnError) {
    const fs::path path = scratch("garbage.png");
    {
        std::FILE* f = std::fopen(path.c_str(), "wb");
        std::fputs("this is not a png", f);
        std::fclose(f);
    }
    EXPECT_THROW(io::read_image(path), Error);
    EXPECT_THROW(io::read_image(scratch("does_not_exist.png")), Error);
}

TEST(ImageIO, Tiff16RoundTripIsExact) {
    std::vector<uint16_t> pixels = {0, 1, 32768, 65535, 1234, 4321};
    const fs::path path = scratch("round.tif");
    io::write_image(path, {3, 2, 1, io::PixelType::u16, pixels.data()});
    io::FloatImage back = io::read_image(path);
    ASSERT_EQ(back.pixels.size(), pixels.size());
    for (size_t i = 0; i < pixels.size(); ++i)
        EXPECT_EQ(int(back.pixels[i] * 65535.0f + 0.5f), int(pixels[i]));
}
