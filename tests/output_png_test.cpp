// The frame files' fast paths against their references: the PNG encoder's files decode (by
// OpenImageIO) to exactly the samples given, for every filter, level and channel count, with
// the same bytes for any thread count; the sRGB table equals linear_to_srgb's rounding.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <tbb/global_control.h>
#include <zlib.h>

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
#include "raster/output/adler32.h"
#include "raster/output/exr_compression.h"
#include "raster/output/frame_stream.h"
#include "raster/output/frame_encoding.h"
#include "raster/output/png_encoder.h"
#include "raster/output/png_paeth.h"
#include "raster/output/rle_deflate.h"
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

// The reference RleDeflate is held to: zlib itself, one deflate() call over all of `data`.
std::vector<uint8_t> zlib_run_length(std::span<const uint8_t> data, bool last, int level = 1) {
    z_stream z{};
    EXPECT_EQ(deflateInit2(&z, level, Z_DEFLATED, -15, 9, Z_RLE), Z_OK);
    std::vector<uint8_t> out(deflateBound(&z, uLong(data.size())) + 64);
    z.next_in = const_cast<uint8_t*>(data.data());
    z.avail_in = uInt(data.size());
    z.next_out = out.data();
    z.avail_out = uInt(out.size());
    const int status = deflate(&z, last ? Z_FINISH : Z_SYNC_FLUSH);
    EXPECT_EQ(status, last ? Z_STREAM_END : Z_OK);
    out.resize(out.size() - z.avail_out);
    deflateEnd(&z);
    return out;
}

// Byte strings of every kind RleDeflate must code as zlib does: runs of every length around
// the 3..258 limits, literals, incompressible stretches (stored blocks), and frequencies that
// overflow 15-bit codes.
std::vector<std::pair<std::string, std::vector<uint8_t>>> deflate_inputs() {
    std::vector<std::pair<std::string, std::vector<uint8_t>>> inputs;
    std::mt19937 rng(11);
    const auto random_bytes = [&](size_t n) {
        std::vector<uint8_t> v(n);
        for (uint8_t& b : v) b = uint8_t(rng());
        return v;
    };
    for (size_t n : {size_t(0), size_t(1), size_t(2), size_t(3), size_t(4), size_t(65), size_t(66), size_t(67),
                     size_t(259), size_t(300)}) {
        inputs.emplace_back("random " + std::to_string(n), random_bytes(n));
        inputs.emplace_back("zeros " + std::to_string(n), std::vector<uint8_t>(n, 0));
    }
    // Around the block size (32767 symbols) and the window's slide (64 KiB - 262), and more
    // than the window: random bytes are all literals, so blocks end exactly there.
    for (size_t n : {size_t(32766), size_t(32767), size_t(32768), size_t(65273), size_t(65274), size_t(65280),
                     size_t(70000), size_t(200000)})
        inputs.emplace_back("random " + std::to_string(n), random_bytes(n));
    inputs.emplace_back("zeros 1M", std::vector<uint8_t>(size_t(1) << 20, 7));
    // Runs of random lengths (1 .. 600) of random bytes from a small alphabet.
    for (int alphabet : {2, 5, 256}) {
        std::vector<uint8_t> v;
        while (v.size() < 300000) v.insert(v.end(), size_t(1 + rng() % 600), uint8_t(rng() % unsigned(alphabet)));
        inputs.emplace_back("runs over " + std::to_string(alphabet), v);
    }
    // Short runs only (1 .. 4), where literals and matches alternate.
    {
        std::vector<uint8_t> v;
        while (v.size() < 150000) v.insert(v.end(), size_t(1 + rng() % 4), uint8_t(rng() % 16));
        inputs.emplace_back("short runs", v);
    }
    // Fibonacci frequencies: the Huffman depths exceed 15 and must be limited.
    {
        std::vector<uint8_t> v;
        uint32_t a = 1, b = 1;
        for (int sym = 0; sym < 22; ++sym) {
            v.insert(v.end(), a, uint8_t(sym * 11));
            const uint32_t c = a + b;
            a = b;
            b = c;
        }
        std::shuffle(v.begin(), v.end(), rng);
        inputs.emplace_back("fibonacci", v);
    }
    // Filtered image rows, as the PNG encoder hands them over.
    {
        const int w = 640;
        const std::vector<uint8_t> p = test_pixels(w, 64, 4, 5);
        std::vector<uint8_t> v;
        for (int y = 0; y < 64; ++y) {
            v.push_back(4);
            for (int x = 0; x < 4 * w; ++x) v.push_back(uint8_t(p[size_t(y * 4 * w + x)] - (x >= 4 ? p[size_t(y * 4 * w + x - 4)] : 0)));
        }
        inputs.emplace_back("image rows", v);
    }
    return inputs;
}

}  // namespace

TEST(RleDeflate, SameBytesAsZlibRunLength) {
    output::RleDeflate deflate;
    for (const auto& [what, data] : deflate_inputs())
        for (bool last : {false, true}) {
            const std::span<const uint8_t> ours = deflate.compress(data, last);
            const std::vector<uint8_t> zlib = zlib_run_length(data, last);
            ASSERT_EQ(std::vector<uint8_t>(ours.begin(), ours.end()), zlib) << what << (last ? ", last" : "");
        }
    // zlib's level does not change run-length matching.
    const std::vector<uint8_t> data = deflate_inputs().back().second;
    const std::span<const uint8_t> ours = deflate.compress(data, true);
    EXPECT_EQ(std::vector<uint8_t>(ours.begin(), ours.end()), zlib_run_length(data, true, 9));
}

TEST(Adler32, EqualsZlibsForEveryLengthAndStart) {
    std::mt19937 rng(5);
    std::vector<uint8_t> data(20000);
    for (uint8_t& b : data) b = uint8_t(rng());
    std::vector<uint8_t> ones(20000, 0xFF);  // the largest sums
    for (const std::vector<uint8_t>* d : {&data, &ones})
        for (size_t n : {size_t(0), size_t(1), size_t(31), size_t(32), size_t(33), size_t(5551), size_t(5552),
                         size_t(5553), size_t(11104), size_t(20000)}) {
            EXPECT_EQ(output::adler32_update(1, d->data(), n), uint32_t(adler32(1, d->data(), uInt(n)))) << n;
            // Continued from a checksum part way.
            const uint32_t start = uint32_t(adler32(1, d->data(), 1000));
            EXPECT_EQ(output::adler32_update(start, d->data() + 1000, n / 2),
                      uint32_t(adler32(start, d->data() + 1000, uInt(n / 2)))) << n;
        }
}

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

// The vector Paeth filter against the byte-by-byte predictor: every (a, b, c) once, as the
// bytes of one wide "pixel" (bpp = 65536: byte j of the second pixel has a = j >> 8 to its
// left, b = j & 255 above, c above-left), then random rows of every length up to a few vectors
// and every bpp the encoder uses, and a 1080p row.
TEST(PngPaeth, FastEqualsTheReferenceForEveryTripleAndRowShape) {
    constexpr size_t kPixel = 65536;
    std::mt19937 rng(4);
    std::vector<uint8_t> row(2 * kPixel), up(2 * kPixel), fast(2 * kPixel), reference(2 * kPixel);
    for (size_t j = 0; j < kPixel; ++j) {
        row[j] = uint8_t(j >> 8);
        up[kPixel + j] = uint8_t(j);
        row[kPixel + j] = uint8_t(rng());
    }
    for (int c = 0; c < 256; ++c) {
        std::fill_n(up.begin(), kPixel, uint8_t(c));
        output::paeth_residuals(row.data(), up.data(), row.size(), kPixel, fast.data());
        output::paeth_residuals_reference(row.data(), up.data(), row.size(), kPixel, reference.data());
        ASSERT_TRUE(fast == reference) << "c = " << c;
    }
    for (size_t bpp = 1; bpp <= 4; ++bpp) {
        for (size_t n : {size_t(1920) * bpp, size_t(0)}) {
            for (size_t length = n; length <= (n == 0 ? 260 : n); ++length) {
                std::vector<uint8_t> r(length), u(length), f(length + 1, 0xA5), ref(length + 1, 0xA5);
                for (size_t i = 0; i < length; ++i) r[i] = uint8_t(rng()), u[i] = uint8_t(rng());
                output::paeth_residuals(r.data(), u.data(), length, bpp, f.data());
                output::paeth_residuals_reference(r.data(), u.data(), length, bpp, ref.data());
                ASSERT_TRUE(f == ref) << "bpp " << bpp << " length " << length;  // nothing past the row either
            }
        }
    }
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

TEST(Srgb8, LaneEncodingEqualsTheTableForEveryChannelAcrossTheRange) {
    // Every 4099th float of [0, 2] and the special values, each in every channel position
    // (the lanes' alpha selection), through the lane loop and its scalar tail (odd pixel count).
    std::vector<float> values;
    for (uint32_t b = 0; b <= std::bit_cast<uint32_t>(2.0f); b += 4099) values.push_back(std::bit_cast<float>(b));
    for (float c : {-0.0f, -1.0f, 1.0f, 7.0f, std::numeric_limits<float>::infinity(),
                    -std::numeric_limits<float>::infinity(), std::numeric_limits<float>::denorm_min(),
                    std::numeric_limits<float>::quiet_NaN(), -std::numeric_limits<float>::quiet_NaN()})
        values.push_back(c);
    for (int shift = 0; shift < 4; ++shift) {
        std::vector<glm::vec4> pixels((values.size() + size_t(shift)) / 4 | 1, glm::vec4(0.5f));
        float* flat = &pixels[0].x;
        for (size_t i = 0; i < values.size() && i + size_t(shift) < 4 * pixels.size(); ++i)
            flat[i + size_t(shift)] = values[i];
        std::vector<uint8_t> bytes(4 * pixels.size());
        const bool finite = output::encode_srgb8(pixels.data(), pixels.size(), bytes.data());
        bool all_finite = true;
        for (size_t i = 0; i < bytes.size(); ++i) {
            all_finite &= std::isfinite(flat[i]);
            ASSERT_EQ(bytes[i], i % 4 == 3 ? output::alpha8(flat[i]) : output::srgb8_reference(flat[i]))
                << flat[i] << " at " << i;
        }
        EXPECT_EQ(finite, all_finite);
    }
    std::vector<glm::vec4> ordinary(33, glm::vec4(0.25f, 0.5f, 1.5f, -1.0f));
    std::vector<uint8_t> bytes(4 * ordinary.size());
    EXPECT_TRUE(output::encode_srgb8(ordinary.data(), ordinary.size(), bytes.data()));
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

// EXR frames in each compression (--exr): the lossless ones read back as written, float for
// float; dwaa (lossy colour) within a few percent, alpha exact; the file says which method
// it holds; the streamed (banded) writer takes the setting too.
TEST(ExrCompression, EveryChoiceReadsBackAndIsRecordedInTheFile) {
    Frame frame(67, 41);
    std::mt19937 rng(4);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    for (int y = 0; y < frame.height; ++y)
        for (int x = 0; x < frame.width; ++x)  // a smooth ramp with noise: something to compress
            frame.at(x, y) = glm::vec4(float(x) / 67.0f, float(y) / 41.0f, 0.5f + 0.1f * unit(rng), y < 20 ? 1.0f : 0.5f);
    const fs::path dir = fs::temp_directory_path() / "tessera_exr_compression";
    fs::create_directories(dir);
    for (const output::ExrCompression c : {output::ExrCompression::zip, output::ExrCompression::piz,
                                           output::ExrCompression::dwaa, output::ExrCompression::none}) {
        const std::string name = output::exr_compression_name(c);
        SCOPED_TRACE(name);
        const fs::path path = dir / ("f_" + name + ".exr");
        output::FileSettings settings;
        settings.exr = c;
        output::write_frame(path, frame, settings);
        const io::FloatImage image = io::read_image(path);
        ASSERT_EQ(image.width, frame.width);
        ASSERT_EQ(image.channels, 4);
        float worst = 0.0f;
        for (int y = 0; y < frame.height; ++y)
            for (int x = 0; x < frame.width; ++x)
                for (int ch = 0; ch < 4; ++ch) {
                    const float d = std::fabs(image.at(x, y, ch) - frame.at(x, y)[ch]);
                    if (ch == 3 || c != output::ExrCompression::dwaa) ASSERT_EQ(d, 0.0f) << x << "," << y << " " << ch;
                    worst = std::max(worst, d);
                }
        EXPECT_LT(worst, 0.03f);
        auto in = OIIO::ImageInput::open(path.string());
        ASSERT_TRUE(in);
        EXPECT_EQ(in->spec().get_string_attribute("compression"), name);
    }
    EXPECT_EQ(output::parse_exr_compression("piz"), output::ExrCompression::piz);
    EXPECT_THROW(output::parse_exr_compression("zstd"), std::invalid_argument);
    // Streamed band by band.
    output::FileSettings piz;
    piz.exr = output::ExrCompression::piz;
    {
        output::FrameStream stream(dir / "streamed.exr", frame.width, frame.height, piz);
        stream.write(0, frame);
        stream.commit();
    }
    auto in = OIIO::ImageInput::open((dir / "streamed.exr").string());
    ASSERT_TRUE(in);
    EXPECT_EQ(in->spec().get_string_attribute("compression"), "piz");
}

