// Raw deflate (RFC 1951) with run-length matching only, byte for byte the stream zlib's
// deflate() writes for one call over a whole buffer after
// deflateInit2(s, level 1..9, Z_DEFLATED, -15, 9, Z_RLE), so that PNG frames keep their bytes
// while costing a fraction of zlib's time.
//
// What zlib does with that set-up (zlib 1.2.12 and later, deflate.c and trees.c), restated as
// the rules this encoder follows:
// - Parsing, greedy: at every position but the stream's first, if the next three bytes equal
//   the byte before, emit a match of distance 1 whose length is the run of bytes equal to it,
//   at most 258 and at most the bytes left; otherwise emit the byte as a literal.
// - Blocks: a block is closed after 32767 symbols (memLevel 9: a symbol buffer of 2^15
//   entries, flushed when one short of full), and at the end of the input. Each block is
//   coded as the smallest of stored (only while its bytes are still inside zlib's 64 KiB
//   sliding window, which moves by 32 KiB when the position passes 64 KiB - 262 at a refill),
//   fixed codes or dynamic codes, ties going to fixed, then to dynamic, as zlib's bit counts
//   (opt_len, static_len) decide.
// - Dynamic codes: zlib's Huffman construction (a heap ordered by frequency, then by subtree
//   depth; at least two codes per tree; lengths limited to 15 (7 for the code-length code) by
//   moving the overflow down the bit-length counts), canonical codes, and the code lengths
//   sent with zlib's run-length rules for repeat codes 16, 17 and 18.
// - The end: with `last`, the last block carries BFINAL and the stream is padded to a byte
//   (Z_FINISH); otherwise an empty stored block follows (Z_SYNC_FLUSH), leaving the stream
//   byte-aligned and open for the next band.
//
// Why it is faster: zlib walks its sliding window byte by byte and keeps a hash table that run
// matching never reads (sliding it alone was a tenth of a 1080p frame's CPU time); here runs
// are found 64 bytes per compare (AVX-512BW; 32 on AVX2, eight per word otherwise) and the
// window exists only as the two positions zlib's stored-block decision depends on.
// tests/output_png_test.cpp compares the bytes with zlib's.
#pragma once
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

namespace tessera::output {

class RleDeflate {
public:
    RleDeflate();
    ~RleDeflate();
    RleDeflate(const RleDeflate&) = delete;
    RleDeflate& operator=(const RleDeflate&) = delete;

    // The compressed `data` (see above for `last`), valid until the next call.
    std::span<const uint8_t> compress(std::span<const uint8_t> data, bool last);

private:
    struct Trees;
    void fill_window();
    void literal(uint8_t byte);
    void match(size_t length);
    void flush_block(bool last);
    void reserve(size_t bytes);
    void put_bits(uint64_t value, int count);
    void align_to_byte();

    std::unique_ptr<Trees> trees_;
    const uint8_t* data_ = nullptr;
    size_t size_ = 0;
    // The block in hand: its symbols (a byte 0..255, or 256 + match length - 3) and the
    // literal/length code frequencies; every match has distance 1 (distance code 0).
    std::vector<uint16_t> symbols_;
    size_t symbol_count_ = 0;
    uint32_t match_count_ = 0;
    // zlib's window as positions in the data: its start, how far it has read, the block's
    // start and the position reached (zlib's block_start and strstart, less window_base_).
    size_t window_base_ = 0, read_ = 0, block_start_ = 0, position_ = 0;
    // Output: the bytes so far and the bits not yet a whole byte.
    std::vector<uint8_t> out_;
    size_t out_size_ = 0;
    uint64_t bit_buffer_ = 0;
    int bit_count_ = 0;
};

}  // namespace tessera::output
