#include "raster/output/rle_deflate.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cstring>

#if defined(__AVX512BW__) || defined(__AVX2__)
#include <immintrin.h>
#endif

namespace tessera::output {
namespace {

static_assert(std::endian::native == std::endian::little, "the run search reads bytes as little-endian words");

// RFC 1951 alphabets.
constexpr int kEndOfBlock = 256;
constexpr int kLengthCodes = 29;
constexpr int kLiteralCodes = 256 + 1 + kLengthCodes;  // 286
constexpr int kDistanceCodes = 30;
constexpr int kCodeLengthCodes = 19;
constexpr int kRepeat = 16, kZeros3 = 17, kZeros11 = 18;  // code-length code repeats
constexpr int kMaxBits = 15, kMaxCodeLengthBits = 7;
// zlib's heap holds every node of the largest tree.
constexpr int kHeapSize = 2 * kLiteralCodes + 1;

constexpr uint8_t kLengthExtra[kLengthCodes] = {0, 0, 0, 0, 0, 0, 0, 0, 1, 1, 1, 1, 2, 2, 2,
                                                2, 3, 3, 3, 3, 4, 4, 4, 4, 5, 5, 5, 5, 0};
constexpr uint8_t kDistanceExtra[kDistanceCodes] = {0, 0, 0, 0, 1, 1, 2, 2,  3,  3,  4,  4,  5,  5,  6,
                                                    6, 7, 7, 8, 8, 9, 9, 10, 10, 11, 11, 12, 12, 13, 13};
constexpr uint8_t kCodeLengthExtra[kCodeLengthCodes] = {0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 2, 3, 7};
constexpr uint8_t kCodeLengthOrder[kCodeLengthCodes] = {16, 17, 18, 0, 8, 7, 9, 6, 10, 5, 11, 4, 12, 3, 13, 2, 14, 1, 15};

// zlib's set-up (see the header): window of 2^15 bytes in a buffer of twice that, refilled when
// fewer than 262 bytes (a longest match and the shortest, plus one) lie ahead.
constexpr size_t kMinMatch = 3, kMaxMatch = 258;
constexpr size_t kWindow = size_t(1) << 15, kWindowSpace = 2 * kWindow;
constexpr size_t kMinLookahead = kMaxMatch + kMinMatch + 1;
constexpr size_t kSlideAt = kWindow + (kWindow - kMinLookahead);
constexpr size_t kBlockSymbols = (size_t(1) << 15) - 1;

// Length code (0..28, i.e. 257..285) and its extra bits' base of each match length - 3.
struct LengthCodes {
    std::array<uint8_t, 256> code{};
    std::array<uint16_t, kLengthCodes> base{};
    LengthCodes() {
        int length = 0;
        for (int c = 0; c < kLengthCodes - 1; ++c) {
            base[size_t(c)] = uint16_t(length);
            for (int n = 0; n < (1 << kLengthExtra[c]); ++n) code[size_t(length++)] = uint8_t(c);
        }
        // 258 has a code of its own (285, no extra bits) rather than 284's last value.
        code[255] = kLengthCodes - 1;
        base[kLengthCodes - 1] = 255;
    }
};
const LengthCodes kLengths;

// The fixed codes' lengths (RFC 1951 3.2.6).
struct FixedLengths {
    std::array<uint8_t, 288> literal{};
    std::array<uint8_t, kDistanceCodes> distance{};
    FixedLengths() {
        for (int n = 0; n < 288; ++n) literal[size_t(n)] = uint8_t(n < 144 ? 8 : n < 256 ? 9 : n < 280 ? 7 : 8);
        distance.fill(5);
    }
};
const FixedLengths kFixed;

uint16_t reverse_bits(unsigned code, int length) {
    unsigned r = 0;
    for (int i = 0; i < length; ++i, code >>= 1) r = (r << 1) | (code & 1u);
    return uint16_t(r);
}

// Canonical codes (RFC 1951 3.2.2) of lengths[0 .. n), bit-reversed for LSB-first output.
template <size_t N>
void canonical_codes(const uint16_t* lengths, int n, const std::array<uint16_t, kMaxBits + 1>& count,
                     std::array<uint16_t, N>& codes) {
    std::array<unsigned, kMaxBits + 1> next{};
    unsigned code = 0;
    for (int bits = 1; bits <= kMaxBits; ++bits) {
        code = (code + count[size_t(bits) - 1]) << 1;
        next[size_t(bits)] = code;
    }
    for (int i = 0; i < n; ++i)
        if (lengths[i] != 0) codes[size_t(i)] = reverse_bits(next[lengths[i]]++, lengths[i]);
}

// A Huffman code under construction: frequencies and lengths of every node (leaves first,
// then the internal nodes), codes of the leaves.
struct Tree {
    std::array<uint32_t, kHeapSize> freq{};
    std::array<uint16_t, kHeapSize> length{};
    std::array<uint16_t, 288> code{};
    int max_code = 0;  // the largest code with a length
};

// What makes one alphabet's tree (zlib's static_tree_desc).
struct Alphabet {
    int size;
    int max_length;
    const uint8_t* fixed_length;  // the fixed code's lengths; null: none (the code-length code)
    const uint8_t* extra;         // extra bits of code extra_base + i
    int extra_base;
};
const Alphabet kLiteralAlphabet{kLiteralCodes, kMaxBits, kFixed.literal.data(), kLengthExtra, 257};
const Alphabet kDistanceAlphabet{kDistanceCodes, kMaxBits, kFixed.distance.data(), kDistanceExtra, 0};
const Alphabet kCodeLengthAlphabet{kCodeLengthCodes, kMaxCodeLengthBits, nullptr, kCodeLengthExtra, 0};

// The block's size in bits coded with the dynamic trees and with the fixed ones, as zlib
// counts them (opt_len, static_len: unsigned, and the "at least two codes" rule subtracts
// before it adds, so the arithmetic is modulo 2^64 like zlib's).
struct BlockBits {
    uint64_t dynamic = 0, fixed = 0;
};

// zlib's Huffman construction (trees.c build_tree, gen_bitlen, gen_codes), step for step: the
// lengths it picks among equally good codes depend on the order of its heap, so it is followed
// exactly.
class HuffmanBuilder {
public:
    void build(Tree& t, const Alphabet& a, BlockBits& bits) {
        heap_len_ = 0;
        heap_max_ = kHeapSize;
        int max_code = -1;
        for (int n = 0; n < a.size; ++n) {
            if (t.freq[size_t(n)] != 0) {
                heap_[size_t(++heap_len_)] = max_code = n;
                depth_[size_t(n)] = 0;
            } else {
                t.length[size_t(n)] = 0;
            }
        }
        // At least two codes, so that a code has bits: the missing ones get frequency 1 (and
        // zlib's counts are corrected for them ahead of gen_bitlen adding them).
        while (heap_len_ < 2) {
            const int node = heap_[size_t(++heap_len_)] = max_code < 2 ? ++max_code : 0;
            t.freq[size_t(node)] = 1;
            depth_[size_t(node)] = 0;
            bits.dynamic -= 1;
            if (a.fixed_length) bits.fixed -= a.fixed_length[node];
        }
        t.max_code = max_code;
        for (int n = heap_len_ / 2; n >= 1; --n) sift_down(t, n);
        // Join the two least frequent nodes until one is left; the heap's tail keeps the
        // nodes in the order they left it (the root last).
        int node = a.size;
        do {
            const int n = heap_[1];
            heap_[1] = heap_[size_t(heap_len_--)];
            sift_down(t, 1);
            const int m = heap_[1];
            heap_[size_t(--heap_max_)] = n;
            heap_[size_t(--heap_max_)] = m;
            t.freq[size_t(node)] = t.freq[size_t(n)] + t.freq[size_t(m)];
            depth_[size_t(node)] = uint8_t(std::max(depth_[size_t(n)], depth_[size_t(m)]) + 1);
            parent_[size_t(n)] = parent_[size_t(m)] = uint16_t(node);
            heap_[1] = node++;
            sift_down(t, 1);
        } while (heap_len_ >= 2);
        heap_[size_t(--heap_max_)] = heap_[1];
        lengths(t, a, bits);
        canonical_codes(t.length.data(), t.max_code + 1, count_, t.code);
    }

private:
    bool smaller(const Tree& t, int n, int m) const {
        return t.freq[size_t(n)] < t.freq[size_t(m)] ||
               (t.freq[size_t(n)] == t.freq[size_t(m)] && depth_[size_t(n)] <= depth_[size_t(m)]);
    }

    void sift_down(const Tree& t, int k) {
        const int v = heap_[size_t(k)];
        int j = k << 1;
        while (j <= heap_len_) {
            if (j < heap_len_ && smaller(t, heap_[size_t(j) + 1], heap_[size_t(j)])) ++j;
            if (smaller(t, v, heap_[size_t(j)])) break;
            heap_[size_t(k)] = heap_[size_t(j)];
            k = j;
            j <<= 1;
        }
        heap_[size_t(k)] = v;
    }

    // Depths from the root down (parents leave the heap after their children, so they come
    // first reading the tail forwards), capped at the alphabet's maximum; the leaves pushed
    // past it are then placed by taking codes from the deepest shorter level (gen_bitlen).
    void lengths(Tree& t, const Alphabet& a, BlockBits& bits) {
        count_.fill(0);
        t.length[size_t(heap_[size_t(heap_max_)])] = 0;
        int overflow = 0;
        int h = heap_max_ + 1;
        for (; h < kHeapSize; ++h) {
            const int n = heap_[size_t(h)];
            int length = t.length[parent_[size_t(n)]] + 1;
            if (length > a.max_length) {
                length = a.max_length;
                ++overflow;
            }
            t.length[size_t(n)] = uint16_t(length);
            if (n > t.max_code) continue;  // an internal node
            ++count_[size_t(length)];
            const int extra = n >= a.extra_base ? a.extra[n - a.extra_base] : 0;
            const uint64_t f = t.freq[size_t(n)];
            bits.dynamic += f * uint64_t(length + extra);
            if (a.fixed_length) bits.fixed += f * uint64_t(a.fixed_length[n] + extra);
        }
        if (overflow == 0) return;
        do {
            int length = a.max_length - 1;
            while (count_[size_t(length)] == 0) --length;
            --count_[size_t(length)];
            count_[size_t(length) + 1] += 2;
            --count_[size_t(a.max_length)];
            overflow -= 2;
        } while (overflow > 0);
        for (int length = a.max_length; length != 0; --length) {
            int n = count_[size_t(length)];
            while (n != 0) {
                const int m = heap_[size_t(--h)];
                if (m > t.max_code) continue;
                if (t.length[size_t(m)] != length) {
                    bits.dynamic += (uint64_t(length) - t.length[size_t(m)]) * t.freq[size_t(m)];
                    t.length[size_t(m)] = uint16_t(length);
                }
                --n;
            }
        }
    }

    std::array<int, kHeapSize> heap_{};
    int heap_len_ = 0, heap_max_ = 0;
    std::array<uint8_t, kHeapSize> depth_{};
    std::array<uint16_t, kHeapSize> parent_{};
    std::array<uint16_t, kMaxBits + 1> count_{};
};

// A tree's code lengths 0 .. max_code as the code-length alphabet codes them (zlib's
// scan_tree / send_tree): runs of a length as the length then 16 (3-6 repeats), runs of
// zeros as 17 (3-10) or 18 (11-138). emit(symbol, extra value, extra bits).
template <class Emit>
void code_length_runs(const uint16_t* length, int max_code, const Emit& emit) {
    int previous = -1, next = length[0], count = 0;
    int max_count = next == 0 ? 138 : 7, min_count = next == 0 ? 3 : 4;
    for (int n = 0; n <= max_code; ++n) {
        const int current = next;
        next = n + 1 <= max_code ? length[n + 1] : 0xFFFF;  // no run continues past the end
        if (++count < max_count && current == next) continue;
        if (count < min_count) {
            do emit(current, 0, 0);
            while (--count != 0);
        } else if (current != 0) {
            if (current != previous) {
                emit(current, 0, 0);
                --count;
            }
            emit(kRepeat, count - 3, 2);
        } else if (count <= 10) {
            emit(kZeros3, count - 3, 3);
        } else {
            emit(kZeros11, count - 11, 7);
        }
        count = 0;
        previous = current;
        if (next == 0) max_count = 138, min_count = 3;
        else if (current == next) max_count = 6, min_count = 3;
        else max_count = 7, min_count = 4;
    }
}

// Bit i set when d[i] == d[i - 1], for i in 0..63 (d[-1] .. d[63] readable): one byte compare
// of the 64 bytes with themselves shifted by one on AVX-512BW, two of 32 on AVX2; otherwise
// eight bytes per step, a zero byte of the XOR marked by its top bit and the eight marks
// gathered by a multiply.
uint64_t equal_to_previous(const uint8_t* d) {
#if defined(__AVX512BW__)
    return _mm512_cmpeq_epi8_mask(_mm512_loadu_si512(d), _mm512_loadu_si512(d - 1));
#elif defined(__AVX2__)
    const auto half = [](const uint8_t* h) {
        const __m256i x = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(h));
        const __m256i y = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(h - 1));
        return uint64_t(uint32_t(_mm256_movemask_epi8(_mm256_cmpeq_epi8(x, y))));
    };
    return half(d) | half(d + 32) << 32;
#else
    constexpr uint64_t kLow7 = 0x7F7F7F7F7F7F7F7FULL, kGather = 0x0102040810204080ULL;
    uint64_t mask = 0;
    for (int g = 0; g < 8; ++g) {
        uint64_t a, b;
        std::memcpy(&a, d + 8 * g, 8);
        std::memcpy(&b, d + 8 * g - 1, 8);
        const uint64_t x = a ^ b;
        const uint64_t zero = ~(((x & kLow7) + kLow7) | x | kLow7);  // 0x80 where a byte is 0
        mask |= (((zero >> 7) * kGather) >> 56) << (8 * g);
    }
    return mask;
#endif
}

// How many positions from p on (at most `max`) come before one where a run of at least three
// copies of the byte before it starts (p >= 1; a run needs its three bytes inside [0, n)).
size_t literals_before_run(const uint8_t* d, size_t p, size_t max, size_t n) {
    size_t k = 0;
    while (k < max) {
        const size_t j = p + k;
        if (j + 66 <= n) {
            const uint64_t e = equal_to_previous(d + j);
            const uint64_t beyond = uint64_t(d[j + 64] == d[j + 63]) | uint64_t(d[j + 65] == d[j + 64]) << 1;
            const uint64_t starts = e & (e >> 1 | beyond << 63) & (e >> 2 | beyond << 62);
            if (starts) return std::min(max, k + size_t(std::countr_zero(starts)));
            k += 64;
        } else {
            if (j + 2 < n && d[j] == d[j - 1] && d[j + 1] == d[j - 1] && d[j + 2] == d[j - 1]) return k;
            ++k;
        }
    }
    return max;
}

// The number of bytes from p on equal to d[p - 1], at most `cap` (p + cap <= size): 64 bytes
// per compare on AVX-512BW (the last step a masked load, which reads nothing past `cap`), 32
// on AVX2, otherwise eight bytes per XOR.
size_t run_length(const uint8_t* d, size_t p, size_t cap) {
    const uint8_t b = d[p - 1];
    size_t r = 0;
#if defined(__AVX512BW__)
    const __m512i run = _mm512_set1_epi8(char(b));
    for (; r < cap; r += 64) {
        const __mmask64 inside = cap - r >= 64 ? ~__mmask64(0) : (__mmask64(1) << (cap - r)) - 1;
        const __mmask64 other = _mm512_mask_cmpneq_epi8_mask(inside, _mm512_maskz_loadu_epi8(inside, d + p + r), run);
        if (other) return r + size_t(std::countr_zero(other));
        if (cap - r <= 64) return cap;
    }
    return r;
#else
#if defined(__AVX2__)
    const __m256i run = _mm256_set1_epi8(char(b));
    for (; r + 32 <= cap; r += 32) {
        const __m256i x = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(d + p + r));
        if (const uint32_t other = ~uint32_t(_mm256_movemask_epi8(_mm256_cmpeq_epi8(x, run))))
            return r + size_t(std::countr_zero(other));
    }
#endif
    const uint64_t pattern = 0x0101010101010101ULL * b;
    for (; r + 8 <= cap; r += 8) {
        uint64_t w;
        std::memcpy(&w, d + p + r, 8);
        if (const uint64_t x = w ^ pattern) return r + size_t(std::countr_zero(x)) / 8;
    }
    while (r < cap && d[p + r] == b) ++r;
    return r;
#endif
}

}  // namespace

struct RleDeflate::Trees {
    Tree literal, distance, code_length;
    HuffmanBuilder builder;
    // Per symbol (a byte, or 256 + match length - 3): its bits and their count, for the block's
    // codes (a match's length code, extra bits and distance code together).
    std::array<uint64_t, 512> symbol_bits{};

    void set_symbol_bits(const Tree& lit, const Tree& dist) {
        for (int c = 0; c < 256; ++c)
            symbol_bits[size_t(c)] = uint64_t(lit.code[size_t(c)]) | uint64_t(lit.length[size_t(c)]) << 32;
        const uint64_t dist_code = dist.code[0], dist_length = dist.length[0];
        for (int lc = 0; lc < 256; ++lc) {
            const int code = kLengths.code[size_t(lc)];
            const uint64_t length = lit.length[size_t(257 + code)], extra = kLengthExtra[code];
            const uint64_t value = uint64_t(lit.code[size_t(257 + code)]) |
                                   uint64_t(lc - kLengths.base[size_t(code)]) << length |
                                   dist_code << (length + extra);
            symbol_bits[size_t(256 + lc)] = value | (length + extra + dist_length) << 32;
        }
    }
};

namespace {

// The fixed codes as trees (their lengths and codes).
struct FixedTrees {
    Tree literal, distance;
    FixedTrees() {
        std::array<uint16_t, kMaxBits + 1> count{};
        std::array<uint16_t, 288> lengths{};
        for (size_t n = 0; n < 288; ++n) ++count[lengths[n] = kFixed.literal[n]];
        std::copy(lengths.begin(), lengths.end(), literal.length.begin());
        canonical_codes(lengths.data(), 288, count, literal.code);
        literal.max_code = kLiteralCodes - 1;
        count.fill(0);
        for (size_t n = 0; n < kDistanceCodes; ++n) ++count[distance.length[n] = kFixed.distance[n]];
        canonical_codes(distance.length.data(), kDistanceCodes, count, distance.code);
        distance.max_code = kDistanceCodes - 1;
    }
};
const FixedTrees kFixedTrees;

}  // namespace

RleDeflate::RleDeflate() : trees_(std::make_unique<Trees>()), symbols_(kBlockSymbols) {}
RleDeflate::~RleDeflate() = default;

void RleDeflate::reserve(size_t bytes) {
    if (out_.size() < out_size_ + bytes + 8) out_.resize(std::max(out_.size() * 2, out_size_ + bytes + 8));
}

void RleDeflate::put_bits(uint64_t value, int count) {
    // bit_count_ < 32 on entry and count <= 32: the buffer never holds more than 63 bits.
    bit_buffer_ |= value << bit_count_;
    bit_count_ += count;
    if (bit_count_ >= 32) {
        const uint32_t word = uint32_t(bit_buffer_);
        std::memcpy(out_.data() + out_size_, &word, 4);
        out_size_ += 4;
        bit_buffer_ >>= 32;
        bit_count_ -= 32;
    }
}

void RleDeflate::align_to_byte() {
    while (bit_count_ > 0) {
        out_[out_size_++] = uint8_t(bit_buffer_);
        bit_buffer_ >>= 8;
        bit_count_ -= 8;
    }
    bit_buffer_ = 0;
    bit_count_ = 0;
}

void RleDeflate::fill_window() {
    // zlib's fill_window as positions: slide by half the buffer once the position is past
    // kSlideAt, then read as much as the buffer holds.
    do {
        size_t more = kWindowSpace - (read_ - window_base_);
        if (position_ - window_base_ >= kSlideAt) {
            window_base_ += kWindow;
            more += kWindow;
        }
        if (read_ == size_) break;
        read_ += std::min(more, size_ - read_);
    } while (read_ - position_ < kMinLookahead && read_ < size_);
}

void RleDeflate::literal(uint8_t byte) { symbols_[symbol_count_++] = byte; }

void RleDeflate::match(size_t length) {
    symbols_[symbol_count_++] = uint16_t(256 + length - kMinMatch);
    ++match_count_;
}

namespace {

// k literals: bytes widened to symbols, a loop the compiler vectorises (kept out of line, where
// the __restrict parameters keep their meaning).
[[gnu::noinline]] void widen(const uint8_t* __restrict from, uint16_t* __restrict to, size_t k) {
    for (size_t i = 0; i < k; ++i) to[i] = from[i];
}

// The literal/length code of each symbol (a byte, or 256 + match length - 3).
struct SymbolCodes {
    std::array<uint16_t, 512> code{};
    SymbolCodes() {
        for (int c = 0; c < 256; ++c) code[size_t(c)] = uint16_t(c);
        for (int lc = 0; lc < 256; ++lc) code[size_t(256 + lc)] = uint16_t(257 + kLengths.code[size_t(lc)]);
    }
};
const SymbolCodes kSymbolCodes;

// The block's literal/length code frequencies, counted into four tables in turn so that
// runs of one symbol do not chain their increments through one counter.
void count_codes(const uint16_t* symbols, size_t n, uint32_t* freq) {
    std::array<std::array<uint32_t, kLiteralCodes>, 4> part{};
    size_t i = 0;
    for (; i + 4 <= n; i += 4)
        for (size_t k = 0; k < 4; ++k) ++part[k][kSymbolCodes.code[symbols[i + k]]];
    for (; i < n; ++i) ++part[0][kSymbolCodes.code[symbols[i]]];
    for (size_t c = 0; c < size_t(kLiteralCodes); ++c) freq[c] = part[0][c] + part[1][c] + part[2][c] + part[3][c];
}

}  // namespace

std::span<const uint8_t> RleDeflate::compress(std::span<const uint8_t> data, bool last) {
    data_ = data.data();
    size_ = data.size();
    window_base_ = read_ = block_start_ = position_ = 0;
    out_size_ = 0;
    bit_buffer_ = 0;
    bit_count_ = 0;
    const uint8_t* d = data_;
    for (;;) {
        if (read_ - position_ <= kMaxMatch) {
            fill_window();
            if (read_ == position_) break;
        }
        const size_t ahead = read_ - position_;
        if (position_ > 0 && ahead >= kMinMatch) {
            // Literals up to the next run, within the block and before the next refill (whose
            // slide decides whether a stored block is possible, so it must happen where zlib's
            // does: at the first symbol with at most kMaxMatch bytes ahead).
            const size_t max = std::min(ahead > kMaxMatch ? ahead - kMaxMatch : 1, kBlockSymbols - symbol_count_);
            const size_t k = literals_before_run(d, position_, max, size_);
            widen(d + position_, symbols_.data() + symbol_count_, k);
            symbol_count_ += k;
            position_ += k;
            if (symbol_count_ == kBlockSymbols) {
                flush_block(false);
                continue;
            }
            if (k == max) continue;
            const size_t length = run_length(d, position_, std::min(kMaxMatch, read_ - position_));
            match(length);
            position_ += length;
        } else {
            literal(d[position_++]);
        }
        if (symbol_count_ == kBlockSymbols) flush_block(false);
    }
    if (last) {
        flush_block(true);
    } else {
        if (symbol_count_ > 0) flush_block(false);
        // Z_SYNC_FLUSH: an empty stored block.
        reserve(16);
        put_bits(0, 3);
        align_to_byte();
        const uint8_t empty[4] = {0, 0, 0xFF, 0xFF};
        std::memcpy(out_.data() + out_size_, empty, 4);
        out_size_ += 4;
    }
    return {out_.data(), out_size_};
}

void RleDeflate::flush_block(bool last) {
    Trees& t = *trees_;
    BlockBits bits;
    count_codes(symbols_.data(), symbol_count_, t.literal.freq.data());
    t.literal.freq[kEndOfBlock] = 1;
    t.distance.freq.fill(0);
    t.distance.freq[0] = match_count_;
    t.builder.build(t.literal, kLiteralAlphabet, bits);
    t.builder.build(t.distance, kDistanceAlphabet, bits);
    t.code_length.freq.fill(0);
    const auto count = [&](int symbol, int, int) { ++t.code_length.freq[size_t(symbol)]; };
    code_length_runs(t.literal.length.data(), t.literal.max_code, count);
    code_length_runs(t.distance.length.data(), t.distance.max_code, count);
    t.builder.build(t.code_length, kCodeLengthAlphabet, bits);
    int max_order = kCodeLengthCodes - 1;  // the last code length sent
    for (; max_order >= 3; --max_order)
        if (t.code_length.length[kCodeLengthOrder[max_order]] != 0) break;
    bits.dynamic += 3 * (uint64_t(max_order) + 1) + 5 + 5 + 4;

    // Bytes with the 3-bit header, rounded up; ties go to the fixed codes.
    uint64_t best = (bits.dynamic + 3 + 7) >> 3;
    const uint64_t fixed = (bits.fixed + 3 + 7) >> 3;
    if (fixed <= best) best = fixed;
    const size_t stored = position_ - block_start_;
    const bool in_window = block_start_ >= window_base_;
    reserve(stored + symbol_count_ * 5 + 1024);
    if (stored + 4 <= best && in_window) {
        put_bits(last ? 1 : 0, 3);
        align_to_byte();
        const uint8_t lengths[4] = {uint8_t(stored), uint8_t(stored >> 8), uint8_t(~stored), uint8_t(~stored >> 8)};
        std::memcpy(out_.data() + out_size_, lengths, 4);
        std::memcpy(out_.data() + out_size_ + 4, data_ + block_start_, stored);
        out_size_ += 4 + stored;
    } else {
        const Tree* lit = &t.literal;
        const Tree* dist = &t.distance;
        if (fixed == best) {
            put_bits(2 + (last ? 1 : 0), 3);
            lit = &kFixedTrees.literal;
            dist = &kFixedTrees.distance;
        } else {
            put_bits(4 + (last ? 1 : 0), 3);
            put_bits(uint64_t(t.literal.max_code + 1 - 257), 5);
            put_bits(uint64_t(t.distance.max_code + 1 - 1), 5);
            put_bits(uint64_t(max_order + 1 - 4), 4);
            for (int rank = 0; rank <= max_order; ++rank)
                put_bits(t.code_length.length[kCodeLengthOrder[rank]], 3);
            const auto send = [&](int symbol, int value, int extra) {
                put_bits(t.code_length.code[size_t(symbol)], t.code_length.length[size_t(symbol)]);
                if (extra) put_bits(uint64_t(value), extra);
            };
            code_length_runs(t.literal.length.data(), t.literal.max_code, send);
            code_length_runs(t.distance.length.data(), t.distance.max_code, send);
        }
        t.set_symbol_bits(*lit, *dist);
        // The symbols, branch-free: eight bytes stored at every step, the pointer moved by the
        // whole bytes (at most 7 + 32 bits are pending; reserve() leaves 8 bytes of slack).
        uint64_t buffer = bit_buffer_;
        unsigned count = unsigned(bit_count_);
        uint8_t* o = out_.data() + out_size_;
        const uint64_t* table = t.symbol_bits.data();
        const uint16_t* symbol = symbols_.data();  // locals: the stores below cannot move them
        const size_t n = symbol_count_;
        for (size_t i = 0; i < n; ++i) {
            const uint64_t e = table[symbol[i]];
            buffer |= (e & 0xFFFFFFFFu) << count;
            count += unsigned(e >> 32);
            std::memcpy(o, &buffer, 8);
            o += count >> 3;
            buffer >>= count & ~7u;
            count &= 7u;
        }
        out_size_ = size_t(o - out_.data());
        bit_buffer_ = buffer;
        bit_count_ = int(count);
        put_bits(lit->code[kEndOfBlock], lit->length[kEndOfBlock]);
        if (last) align_to_byte();
    }
    match_count_ = 0;
    symbol_count_ = 0;
    block_start_ = position_;
}

}  // namespace tessera::output
