// The frame files' fast paths against their references: the PNG encoder's files decode (by
// OpenImageIO) to exactly the samples given, for every filter, level and channel count, with
// the same bytes for any thread count; the sRGB table equals linear_to_srgb's rounding.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <bit>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>

#include "raster/core/atomic_file.h"
#include "raster/core/color_space.h"
#include "raster/core/error.h"
#include "raster/io/image_io.h"
#include "raster/output/frame_encoding.h"
#include "raster/output/png_encoder.h"
#include "raster/output/srgb8.h"

namespace fs = std::filesystem;
using namespace tessera;
using output::PngFilter;
using output::PngSettings;

namespace {

// Smooth gradients with noise on top: every filter has residuals of all sizes to code.
std::vector<uint8_t> test_pixels(int w, int h, int channels, uint32_t seed) {
    std::mt19937 rng(seed);
    std::vector<uint8_t> p(size_t(w) * size_t(h) * size_t(channels));
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < channels; ++c)
                p[(size_t(y) * size_t(w) + size_t(x)) * size_t(channels) + size_t(c)] =
                    uint8_t(x * (c + 1) + y * 3 + int(rng() % 7));
    return p;
}

// Decoded by OpenImageIO as stored: PNG alpha is unassociated, so the reader is told not to
// premultiply.
void expect_decodes_to(const std::vector<uint8_t>& file, const std::vector<uint8_t>& pixels, int w, int h,
                       int channels, const std::string& what) {
    const fs::path path = fs::temp_directory_path() / "tessera_output_png_test.png";
    write_file_atomically(path, std::as_bytes(std::span(file.data(), file.size())));
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);
    auto in = OIIO::ImageInput::open(path.string(), &config);
    ASSERT_TRUE(in) << what;
    const OIIO::ImageSpec& spec = in->spec();
    ASSERT_EQ(spec.width, w) << what;
    ASSERT_EQ(spec.height, h) << what;
    ASSERT_EQ(spec.nchannels, channels) << what;
    std::vector<uint8_t> decoded(pixels.size());
    ASSERT_TRUE(in->read_image(0, 0, 0, channels, OIIO::TypeDesc::UINT8, decoded.data())) << what;
    EXPECT_TRUE(decoded == pixels) << what;
}

}  // namespace

TEST(PngEncoder, DecodesToTheSamplesForEveryFilterLevelAndChannelCount) {
    // 150 rows: two full bands of kPngBandRows and a partial one.
    const int w = 37, h = 150;
    for (int channels = 1; channels <= 4; ++channels) {
        const std::vector<uint8_t> pixels = test_pixels(w, h, channels, uint32_t(channels));
        for (PngFilter f : {PngFilter::none, PngFilter::sub, PngFilter::up, PngFilter::average, PngFilter::paeth,
                            PngFilter::adaptive})
            for (const auto& [level, rle] : {std::pair{0, false}, std::pair{1, true}, std::pair{6, false}}) {
                const PngSettings s{level, f, rle};
                expect_decodes_to(output::encode_png(pixels.data(), w, h, channels, s), pixels, w, h, channels,
                                  "channels " + std::to_string(channels) + " filter " + std::to_string(int(f)) +
                                      " level " + std::to_string(level));
            }
        expect_decodes_to(output::encode_png(pixels.data(), w, h, channels, PngSettings::smallest()), pixels, w, h,
                          channels, "smallest");
    }
    const std::vector<uint8_t> one = {200, 10, 20, 255};
    expect_decodes_to(output::encode_png(one.data(), 1, 1, 4), one, 1, 1, 4, "1x1");
}

TEST(PngEncoder, SameBytesWithOneAndTwoThreads) {
    const int w = 64, h = 200;
    const std::vector<uint8_t> pixels = test_pixels(w, h, 4, 7);
    std::vector<uint8_t> one, two;
    {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
        one = output::encode_png(pixels.data(), w, h, 4);
    }
    {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
        two = output::encode_png(pixels.data(), w, h, 4);
    }
    EXPECT_EQ(one, two);
}

TEST(PngEncoder, RejectsWhatItCannotWrite) {
    const std::vector<uint8_t> pixels(16, 0);
    EXPECT_THROW(output::encode_png(pixels.data(), 0, 4, 1), std::invalid_argument);
    EXPECT_THROW(output::encode_png(pixels.data(), 4, -1, 1), std::invalid_argument);
    EXPECT_THROW(output::encode_png(pixels.data(), 2, 2, 5), std::invalid_argument);
    EXPECT_THROW(output::encode_png(pixels.data(), 2, 2, 0), std::invalid_argument);
    EXPECT_THROW(output::encode_png(pixels.data(), 2, 2, 4, PngSettings{10, PngFilter::none, false}),
                 std::invalid_argument);
    EXPECT_THROW(output::encode_png(pixels.data(), 1 << 30, 1, 4), std::invalid_argument);
    EXPECT_EQ(output::parse_png_compression("small").level, 9);
    EXPECT_EQ(output::parse_png_compression("fast").filter, PngFilter::paeth);
    EXPECT_THROW(output::parse_png_compression("tiny"), std::invalid_argument);
}

TEST(Srgb8, TableEqualsTheDefinitionAroundEveryLevelAndAcrossTheRange) {
    // Either side of each level's threshold, where a wrong table would show first.
    for (int k = 1; k < 256; ++k) {
        uint32_t lo = 0, hi = std::bit_cast<uint32_t>(1.0f);
        while (hi - lo > 1) {
            const uint32_t mid = lo + (hi - lo) / 2;
            (output::srgb8_reference(std::bit_cast<float>(mid)) >= k ? hi : lo) = mid;
        }
        for (uint32_t b = hi - 3; b <= hi + 3; ++b) {
            const float c = std::bit_cast<float>(b);
            ASSERT_EQ(output::srgb8(c), output::srgb8_reference(c)) << c;
        }
    }
    // A sweep over the bit patterns of [0, 2] (every 4099th float).
    for (uint32_t b = 0; b <= std::bit_cast<uint32_t>(2.0f); b += 4099) {
        const float c = std::bit_cast<float>(b);
        ASSERT_EQ(output::srgb8(c), output::srgb8_reference(c)) << c;
    }
    for (float c : {-0.0f, -1.0f, 1.0f, 7.0f, std::numeric_limits<float>::infinity(),
                    -std::numeric_limits<float>::infinity(), std::numeric_limits<float>::denorm_min(),
                    std::numeric_limits<float>::quiet_NaN()})
        EXPECT_EQ(output::srgb8(c), output::srgb8_reference(c)) << c;
}

TEST(Srgb8, FrameEncodingEqualsTheDefinitionPerChannel) {
    // Values across and beyond [0, 1], NaN and infinities in every channel, alpha included.
    Frame frame(19, 7);
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> value(-0.25f, 1.25f);
    for (glm::vec4& p : frame.pixels) p = {value(rng), value(rng) * value(rng), value(rng), value(rng)};
    frame.at(0, 0) = glm::vec4(std::numeric_limits<float>::quiet_NaN());
    frame.at(1, 0) = glm::vec4(std::numeric_limits<float>::infinity());
    frame.at(2, 0) = glm::vec4(-std::numeric_limits<float>::infinity());
    const std::vector<uint8_t> bytes = output::encode_srgb8(frame);
    ASSERT_EQ(bytes.size(), frame.pixels.size() * 4);
    for (size_t i = 0; i < frame.pixels.size(); ++i) {
        const glm::vec4 p = frame.pixels[i];
        for (int c = 0; c < 3; ++c)
            ASSERT_EQ(bytes[4 * i + size_t(c)], uint8_t(linear_to_srgb(p[c]) * 255.0f + 0.5f)) << i << " " << c;
        const float a = p.a > 0.0f ? std::min(p.a, 1.0f) : 0.0f;
        ASSERT_EQ(bytes[4 * i + 3], uint8_t(a * 255.0f + 0.5f)) << i;
    }
}

TEST(PngEncoder, WriteFrameGoesThroughItAndFailsWithoutAHalfFile) {
    Frame frame(70, 66, glm::vec4(0.25f, 0.5f, 1.0f, 1.0f));
    const fs::path dir = fs::temp_directory_path() / "tessera_output_png_frames";
    fs::create_directories(dir);
    output::write_frame(dir / "f.png", frame);
    const io::FloatImage image = io::read_image(dir / "f.png");
    EXPECT_EQ(int(image.at(69, 65, 1) * 255.0f + 0.5f), output::srgb8_reference(0.5f));
    EXPECT_THROW(output::write_frame(dir / "missing" / "f.png", frame), Error);
    EXPECT_FALSE(fs::exists(dir / "missing"));
}
