#include "raster/output/png_encoder.h"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <zlib.h>

#include <algorithm>
#include <cstdlib>
#include <initializer_list>
#include <stdexcept>

#include "raster/output/adler32.h"
#include "raster/output/png_paeth.h"
#include "raster/output/rle_deflate.h"

namespace tessera::output {
namespace {

// The bands compress on oneTBB's workers, except under ThreadSanitizer: the encoder runs on
// the background frame writers, which TSan checks, and TSan cannot see the synchronisation
// inside an uninstrumented libtbb, so it would report the join of every parallel_for as a race.
// The bytes are the same either way (each band is compressed on its own and joined in order).
#if defined(__SANITIZE_THREAD__)
constexpr bool kBandsInParallel = false;
#elif defined(__has_feature)
#if __has_feature(thread_sanitizer)
constexpr bool kBandsInParallel = false;
#else
constexpr bool kBandsInParallel = true;
#endif
#else
constexpr bool kBandsInParallel = true;
#endif

// Section 9.2 filter types.
enum : uint8_t { kNone = 0, kSub = 1, kUp = 2, kAverage = 3, kPaeth = 4 };

// One filtered row: out[0] = the filter type, out[1 .. n] the residuals. `up` is the previous
// row (zeros above the first row), `bpp` the bytes per pixel.
void filter_row(uint8_t type, const uint8_t* row, const uint8_t* up, size_t n, size_t bpp, uint8_t* out) {
    out[0] = type;
    uint8_t* r = out + 1;
    switch (type) {
        case kNone: std::copy_n(row, n, r); break;
        case kSub:
            for (size_t i = 0; i < n; ++i) r[i] = uint8_t(row[i] - (i >= bpp ? row[i - bpp] : 0));
            break;
        case kUp:
            for (size_t i = 0; i < n; ++i) r[i] = uint8_t(row[i] - up[i]);
            break;
        case kAverage:
            for (size_t i = 0; i < n; ++i) r[i] = uint8_t(row[i] - ((i >= bpp ? row[i - bpp] : 0) + up[i]) / 2);
            break;
        default: paeth_residuals(row, up, n, bpp, r); break;
    }
}

// libpng's heuristic: the filter whose residuals, read as signed bytes, sum to the least.
uint8_t choose_filter(const uint8_t* row, const uint8_t* up, size_t n, size_t bpp, std::vector<uint8_t>& scratch) {
    uint8_t best = kNone;
    uint64_t best_sum = ~uint64_t(0);
    for (uint8_t type = kNone; type <= kPaeth; ++type) {
        filter_row(type, row, up, n, bpp, scratch.data());
        uint64_t sum = 0;
        for (size_t i = 1; i <= n; ++i) sum += uint64_t(std::abs(int(int8_t(scratch[i]))));
        if (sum < best_sum) {
            best_sum = sum;
            best = type;
        }
    }
    return best;
}

void put32(uint8_t* out, uint32_t v) {
    for (int i = 0; i < 4; ++i) out[i] = uint8_t(v >> (24 - 8 * i));
}

// A chunk (section 5.3): length, type, data, CRC of type and data. `data` is given in parts
// (the zlib header, a band's deflate bytes, the Adler-32 trailer) so none is copied twice.
void put_chunk(std::vector<uint8_t>& out, const char type[4], std::initializer_list<std::span<const uint8_t>> data) {
    size_t n = 0;
    for (const std::span<const uint8_t> part : data) n += part.size();
    const size_t start = out.size();
    out.resize(start + 8 + n + 4);
    uint8_t* p = out.data() + start;
    put32(p, uint32_t(n));
    std::copy_n(type, 4, p + 4);
    uLong crc = crc32(0, p + 4, 4);
    p += 8;
    for (const std::span<const uint8_t> part : data) {
        if (part.empty()) continue;
        std::copy(part.begin(), part.end(), p);
        crc = crc32(crc, p, uInt(part.size()));
        p += part.size();
    }
    put32(p, uint32_t(crc));
}

// Filters rows [y0, y1) into `filtered` (each row its filter byte then the residuals).
void filter_band(const uint8_t* pixels, int width, int channels, int y0, int y1, const PngSettings& s,
                 std::vector<uint8_t>& filtered, std::vector<uint8_t>& zeros, std::vector<uint8_t>& scratch) {
    const size_t n = size_t(width) * size_t(channels), bpp = size_t(channels);
    if (y0 == 0 && zeros.size() < n) zeros.assign(n, 0);
    if (s.filter == PngFilter::adaptive && scratch.size() < n + 1) scratch.resize(n + 1);
    filtered.resize(size_t(y1 - y0) * (n + 1));
    for (int y = y0; y < y1; ++y) {
        const uint8_t* row = pixels + size_t(y) * n;
        const uint8_t* up = y == 0 ? zeros.data() : row - n;
        uint8_t type = kNone;
        switch (s.filter) {
            case PngFilter::none: type = kNone; break;
            case PngFilter::sub: type = kSub; break;
            case PngFilter::up: type = kUp; break;
            case PngFilter::average: type = kAverage; break;
            case PngFilter::paeth: type = kPaeth; break;
            case PngFilter::adaptive: type = choose_filter(row, up, n, bpp, scratch); break;
        }
        filter_row(type, row, up, n, bpp, filtered.data() + size_t(y - y0) * (n + 1));
    }
}

}  // namespace

// One thread's buffers for compressing bands.
struct PngEncoder::Scratch {
    struct Local {
        std::vector<uint8_t> filtered, zeros, choose;
        RleDeflate rle;
        z_stream z{};
        bool z_ready = false;
        std::vector<uint8_t> z_out;
        ~Local() {
            if (z_ready) deflateEnd(&z);
        }
    };
    tbb::enumerable_thread_specific<Local> local;
};

struct PngEncoder::Band {
    std::vector<uint8_t> deflated;
    uLong adler = 1;
    size_t raw_bytes = 0;
};

PngEncoder::PngEncoder(const PngSettings& settings) : settings_(settings), scratch_(std::make_unique<Scratch>()) {}
PngEncoder::~PngEncoder() = default;

std::span<const uint8_t> PngEncoder::encode(const uint8_t* pixels, int width, int height, int channels) {
    const PngSettings& settings = settings_;
    if (width <= 0 || height <= 0)
        throw std::invalid_argument("png: image size " + std::to_string(width) + "x" + std::to_string(height) +
                                    " is not positive");
    if (channels < 1 || channels > 4) throw std::invalid_argument("png: 1 to 4 channels");
    if (settings.level < 0 || settings.level > 9) throw std::invalid_argument("png: zlib level 0..9");
    // A row plus its filter byte must fit zlib's 32-bit counts with a band of them.
    if (uint64_t(width) * uint64_t(channels) + 1 > (uint64_t(1) << 31) / kPngBandRows)
        throw std::invalid_argument("png: rows too wide");

    const int bands = (height + kPngBandRows - 1) / kPngBandRows;
    if (bands_.size() < size_t(bands)) bands_.resize(size_t(bands));
    const bool run_length = settings.run_length && settings.level >= 1;
    const auto compress = [&](int b) {
        const int y0 = b * kPngBandRows, y1 = std::min(height, y0 + kPngBandRows);
        const bool last = b + 1 == bands;
        Scratch::Local& s = scratch_->local.local();
        Band& band = bands_[size_t(b)];
        filter_band(pixels, width, channels, y0, y1, settings, s.filtered, s.zeros, s.choose);
        band.raw_bytes = s.filtered.size();
        band.adler = adler32_update(1, s.filtered.data(), s.filtered.size());
        if (run_length) {
            const std::span<const uint8_t> out = s.rle.compress(s.filtered, last);
            band.deflated.assign(out.begin(), out.end());
            return;
        }
        // Raw deflate (negative window bits): the zlib header and trailer are written once,
        // around all the bands.
        if (!s.z_ready) {
            if (deflateInit2(&s.z, settings.level, Z_DEFLATED, -15, 9,
                             settings.run_length ? Z_RLE : Z_DEFAULT_STRATEGY) != Z_OK)
                throw std::runtime_error("png: deflateInit2 failed");
            s.z_ready = true;
        } else if (deflateReset(&s.z) != Z_OK) {
            throw std::runtime_error("png: deflateReset failed");
        }
        s.z_out.resize(deflateBound(&s.z, uLong(s.filtered.size())) + 16);
        s.z.next_in = s.filtered.data();
        s.z.avail_in = uInt(s.filtered.size());
        s.z.next_out = s.z_out.data();
        s.z.avail_out = uInt(s.z_out.size());
        const int status = deflate(&s.z, last ? Z_FINISH : Z_SYNC_FLUSH);
        const bool ok = last ? status == Z_STREAM_END : (status == Z_OK && s.z.avail_in == 0 && s.z.avail_out > 0);
        if (!ok) throw std::runtime_error("png: deflate failed");
        band.deflated.assign(s.z_out.data(), s.z_out.data() + (s.z_out.size() - s.z.avail_out));
    };
    if (kBandsInParallel)
        tbb::parallel_for(0, bands, compress);
    else
        for (int b = 0; b < bands; ++b) compress(b);

    std::vector<uint8_t>& out = file_;
    out.assign({0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'});
    static constexpr uint8_t kColourType[5] = {0, 0, 4, 2, 6};  // grey, grey+alpha, RGB, RGBA
    const uint8_t header[13] = {uint8_t(width >> 24), uint8_t(width >> 16), uint8_t(width >> 8), uint8_t(width),
                                uint8_t(height >> 24), uint8_t(height >> 16), uint8_t(height >> 8), uint8_t(height),
                                8, kColourType[channels], 0, 0, 0};
    put_chunk(out, "IHDR", {header});
    const uint8_t intent[1] = {0};  // perceptual
    put_chunk(out, "sRGB", {intent});

    // The zlib stream: a header (32K window, deflate; FCHECK makes it a multiple of 31), the
    // bands, the Adler-32 of all the filtered bytes. One IDAT chunk per band.
    const uint8_t level_bits = settings.level <= 1 ? 0 : settings.level <= 5 ? 1 : settings.level == 6 ? 2 : 3;
    uint8_t zlib_header[2] = {0x78, uint8_t(level_bits << 6)};
    zlib_header[1] = uint8_t(zlib_header[1] + (31 - (zlib_header[0] * 256 + zlib_header[1]) % 31) % 31);
    uLong adler = 1;
    size_t total = out.size() + 12;
    for (int b = 0; b < bands; ++b) {
        const Band& band = bands_[size_t(b)];
        adler = adler32_combine(adler, band.adler, z_off_t(band.raw_bytes));
        total += band.deflated.size() + 12;
    }
    out.reserve(total + 6);
    uint8_t trailer[4];
    put32(trailer, uint32_t(adler));
    for (int b = 0; b < bands; ++b) {
        const std::span<const uint8_t> data = bands_[size_t(b)].deflated;
        put_chunk(out, "IDAT",
                  {std::span<const uint8_t>(zlib_header, b == 0 ? 2 : 0), data,
                   std::span<const uint8_t>(trailer, b + 1 == bands ? 4 : 0)});
    }
    put_chunk(out, "IEND", {});
    return out;
}

std::vector<uint8_t> encode_png(const uint8_t* pixels, int width, int height, int channels,
                                const PngSettings& settings) {
    PngEncoder encoder(settings);
    const std::span<const uint8_t> file = encoder.encode(pixels, width, height, channels);
    return {file.begin(), file.end()};
}

PngSettings parse_png_compression(std::string_view name) {
    if (name == "fast") return PngSettings{};
    if (name == "small") return PngSettings::smallest();
    throw std::invalid_argument("--png: unknown compression '" + std::string(name) + "' (expected fast or small)");
}

}  // namespace tessera::output
