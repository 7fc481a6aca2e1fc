// PNG files (ISO/IEC 15948, "Portable Network Graphics") written by tessera itself, so that
// the cost of an animation frame's file can be chosen and the compression of one frame runs on
// every core.
//
// A PNG's pixels are one zlib stream (RFC 1950) of filtered rows. The rows are cut into
// bands of kPngBandRows and each band is filtered and deflated (RFC 1951) on its own, in
// parallel: every band but the last ends with a sync flush (an empty stored block, which
// leaves the stream byte-aligned and not final), so the bands' raw deflate streams concatenate
// into one valid stream; each band starts with an empty window, which costs little at 64 rows.
// The Adler-32 of the whole is combined from the bands' (adler32_combine) — pigz's method of
// parallel deflate. The band height depends on nothing but the image, so the bytes are the
// same for any thread count.
//
// Samples are stored as given. PNG alpha is unassociated (section 12.8); a renderer's frame is
// opaque wherever it was rendered (rows outside FrameRenderer::set_rows are (0, 0, 0, 0)), so
// no colour is divided by alpha here. (OpenImageIO's writer, used before, divided colour by
// alpha, which for these frames changed nothing.)
//
// Filters (section 9): every row is filtered with `filter`, or with the per-row choice of
// `adaptive` (the smallest sum of absolute signed residuals, libpng's heuristic). Animation
// frames default to the Paeth filter and zlib's run-length strategy (Z_RLE: matches at
// distance 1 only, no hash chains): rendered frames are smooth, so Paeth residuals are
// mostly runs of small values, and on them this is 4-6 times faster than zlib's default
// level 6 with adaptive filters for files 10-20% larger, and faster and smaller than level 1
// (BENCHMARKS.md has the figures). `smallest()` is adaptive filtering at level 9.
#pragma once
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace tessera::output {

enum class PngFilter { none, sub, up, average, paeth, adaptive };

struct PngSettings {
    int level = 1;  // zlib 0 (stored) .. 9 (smallest)
    PngFilter filter = PngFilter::paeth;
    bool run_length = true;  // zlib's Z_RLE strategy instead of its default string matching

    static PngSettings smallest() { return {9, PngFilter::adaptive, false}; }
};

inline constexpr int kPngBandRows = 64;

// "fast" (the default above) or "small" (smallest()); throws std::invalid_argument otherwise.
PngSettings parse_png_compression(std::string_view name);

// The complete file, signature to IEND, of `height` rows of `width` pixels of 8-bit samples
// (`channels`: 1 grey, 2 grey + alpha, 3 RGB, 4 RGBA), rows top to bottom, tightly packed. An
// sRGB chunk says that the samples are sRGB-encoded. Throws std::invalid_argument for a size
// outside 1 .. 2^31 - 1 or a channel count outside 1..4, std::runtime_error if zlib fails.
std::vector<uint8_t> encode_png(const uint8_t* pixels, int width, int height, int channels,
                                const PngSettings& settings = {});

// encode_png for frame after frame: the buffers (filtered rows, compressor state, each band's
// output, the file) are kept from one image to the next, so an animation's frames cost no
// allocation, zeroing or page fault after the first. The run-length settings (run_length
// and level >= 1) compress with RleDeflate (rle_deflate.h), zlib's bytes at a fraction of its
// time; the others with zlib, its stream reset per band rather than made anew.
// Not for concurrent use: one encoder per thread that writes.
class PngEncoder {
public:
    explicit PngEncoder(const PngSettings& settings = {});
    ~PngEncoder();
    PngEncoder(const PngEncoder&) = delete;
    PngEncoder& operator=(const PngEncoder&) = delete;

    // As encode_png; the file is valid until the next call.
    std::span<const uint8_t> encode(const uint8_t* pixels, int width, int height, int channels);
    const PngSettings& settings() const { return settings_; }

private:
    struct Scratch;
    struct Band;
    const PngSettings settings_;
    std::unique_ptr<Scratch> scratch_;
    std::vector<Band> bands_;
    std::vector<uint8_t> file_;
};

}  // namespace tessera::output
