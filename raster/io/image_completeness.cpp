#include "raster/io/image_completeness.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>
#include <zlib.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "raster/io/image_codec.h"

namespace tessera::io {
namespace fs = std::filesystem;

namespace {

// A regular file read at explicit offsets: every read is whole, or the file is not complete.
// (O_NONBLOCK: a FIFO under a frame's name must not hang the check.)
class FileReader {
public:
    explicit FileReader(const fs::path& path) : fd_(::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC)) {
        struct stat st {};
        if (fd_ >= 0 && ::fstat(fd_, &st) == 0 && S_ISREG(st.st_mode)) size_ = uint64_t(st.st_size);
        else close();
    }
    ~FileReader() { close(); }
    FileReader(const FileReader&) = delete;
    FileReader& operator=(const FileReader&) = delete;

    bool open() const { return fd_ >= 0; }
    uint64_t size() const { return size_; }
    // Reads bytes [offset, offset + n) into `out`; false past the end of the file.
    bool read(uint64_t offset, void* out, size_t n) const {
        if (offset > size_ || n > size_ - offset) return false;
        auto* p = static_cast<unsigned char*>(out);
        while (n > 0) {
            const ssize_t got = ::pread(fd_, p, n, off_t(offset));
            if (got <= 0) return false;
            p += got, n -= size_t(got), offset += uint64_t(got);
        }
        return true;
    }

private:
    void close() {
        if (fd_ >= 0) ::close(fd_);
        fd_ = -1;
    }
    int fd_ = -1;
    uint64_t size_ = 0;
};

uint32_t big_endian32(const unsigned char* p) {
    return uint32_t(p[0]) << 24 | uint32_t(p[1]) << 16 | uint32_t(p[2]) << 8 | uint32_t(p[3]);
}

// PNG (ISO/IEC 15948): the signature, then chunks (length, type, data, CRC-32 of type and
// data) from IHDR to IEND, which must end the file. Every CRC is checked, so a chunk
// truncated or overwritten anywhere fails; IHDR gives the size.
bool png_is_complete(const FileReader& file, int width, int height) {
    static const unsigned char signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    unsigned char head[8];
    if (!file.read(0, head, 8) || std::memcmp(head, signature, 8) != 0) return false;
    std::vector<unsigned char> data;
    bool first = true;
    for (uint64_t at = 8;;) {
        if (!file.read(at, head, 8)) return false;
        const uint32_t length = big_endian32(head);
        if (length > 0x7fffffffu) return false;
        uLong crc = crc32(0L, head + 4, 4);
        // Chunk data in pieces of at most 1 MiB (an IDAT may be large).
        uint64_t offset = at + 8;
        for (uint32_t left = length; left > 0;) {
            const uint32_t n = std::min<uint32_t>(left, 1u << 20);
            data.resize(n);
            if (!file.read(offset, data.data(), n)) return false;
            crc = crc32(crc, data.data(), n);
            offset += n, left -= n;
        }
        unsigned char stored[4];
        if (!file.read(offset, stored, 4) || big_endian32(stored) != uint32_t(crc)) return false;
        const std::string type(reinterpret_cast<const char*>(head + 4), 4);
        if (first) {
            unsigned char ihdr[8];
            if (type != "IHDR" || length != 13 || !file.read(at + 8, ihdr, 8)) return false;
            if (big_endian32(ihdr) != uint32_t(width) || big_endian32(ihdr + 4) != uint32_t(height)) return false;
            first = false;
        }
        at = offset + 4;
        if (type == "IEND") return at == file.size();
    }
}

// Integers of a TIFF file, in its byte order.
struct TiffReader {
    const FileReader& file;
    bool little = true;
    bool big = false;  // BigTIFF: 8-byte offsets and counts

    uint64_t get(const unsigned char* p, int bytes) const {
        uint64_t v = 0;
        for (int i = 0; i < bytes; ++i) v |= uint64_t(p[little ? i : bytes - 1 - i]) << (8 * i);
        return v;
    }
};

// Whether bytes [offset, offset + count) hold a zlib stream that inflates to its end (where
// zlib compares the Adler-32 of what it inflated with the one stored).
bool inflates_to_end(const FileReader& file, uint64_t offset, uint64_t count) {
    if (count == 0 || count > (uint64_t(1) << 32)) return false;
    std::vector<unsigned char> in(static_cast<size_t>(count));
    if (!file.read(offset, in.data(), in.size())) return false;
    z_stream z{};
    if (inflateInit(&z) != Z_OK) return false;
    std::array<unsigned char, 1 << 16> out;
    z.next_in = in.data();
    z.avail_in = uInt(in.size());
    int status = Z_OK;
    while (status == Z_OK) {
        z.next_out = out.data();
        z.avail_out = uInt(out.size());
        status = inflate(&z, Z_NO_FLUSH);
        if (status == Z_BUF_ERROR && z.avail_in == 0) break;  // the stream stops short
    }
    inflateEnd(&z);
    return status == Z_STREAM_END;
}

// TIFF 6.0 and BigTIFF: the first image's directory gives its size, its compression and
// where each strip or tile lies. Every one must lie within the file; deflate-compressed ones
// (as tessera writes them) are inflated to their end, which checks their bytes ("checked");
// others can only be decoded ("decode").
enum class Tiff { incomplete, checked, decode };

Tiff tiff_completeness(const FileReader& file, int width, int height) {
    const Tiff incomplete = Tiff::incomplete;
    unsigned char head[16];
    if (!file.read(0, head, 8)) return incomplete;
    TiffReader tiff{file};
    if (head[0] == 'I' && head[1] == 'I') tiff.little = true;
    else if (head[0] == 'M' && head[1] == 'M') tiff.little = false;
    else return incomplete;
    const uint64_t version = tiff.get(head + 2, 2);
    uint64_t ifd = 0;
    if (version == 42) {
        ifd = tiff.get(head + 4, 4);
    } else if (version == 43) {
        tiff.big = true;
        if (!file.read(0, head, 16) || tiff.get(head + 4, 2) != 8) return incomplete;
        ifd = tiff.get(head + 8, 8);
    } else {
        return incomplete;
    }
    const int count_bytes = tiff.big ? 8 : 2, entry_bytes = tiff.big ? 20 : 12, value_bytes = tiff.big ? 8 : 4;
    unsigned char n_raw[8];
    if (!file.read(ifd, n_raw, size_t(count_bytes))) return incomplete;
    const uint64_t entries = tiff.get(n_raw, count_bytes);
    if (entries == 0 || entries > 4096) return incomplete;
    std::vector<unsigned char> dir(size_t(entries) * size_t(entry_bytes));
    if (!file.read(ifd + uint64_t(count_bytes), dir.data(), dir.size())) return incomplete;

    // A tag's values: inline in the entry when they fit, else at the offset it holds.
    const auto values = [&](const unsigned char* e, std::vector<uint64_t>& out) {
        const uint64_t type = tiff.get(e + 2, 2);
        const uint64_t n = tiff.get(e + 4, tiff.big ? 8 : 4);
        const int size = type == 3 ? 2 : type == 4 ? 4 : type == 16 ? 8 : 0;  // SHORT, LONG, LONG8
        if (size == 0 || n == 0 || n > (uint64_t(1) << 28)) return false;
        std::vector<unsigned char> raw(size_t(n) * size_t(size));
        const unsigned char* field = e + 4 + (tiff.big ? 8 : 4);
        if (raw.size() <= size_t(value_bytes)) std::memcpy(raw.data(), field, raw.size());
        else if (!file.read(tiff.get(field, value_bytes), raw.data(), raw.size())) return false;
        out.resize(size_t(n));
        for (size_t i = 0; i < out.size(); ++i) out[i] = tiff.get(raw.data() + i * size_t(size), size);
        return true;
    };
    std::vector<uint64_t> w, h, compression{1}, offsets, counts, tmp;
    // Where the file's last structure ends: the directory with its next-directory offset, the
    // tag values stored out of line, the strips or tiles. Nothing may follow it (a frame cut
    // short and padded, or overwritten past its end, is not the frame written).
    uint64_t end = ifd + uint64_t(count_bytes) + dir.size() + uint64_t(value_bytes);
    for (uint64_t i = 0; i < entries; ++i) {
        const unsigned char* e = dir.data() + i * uint64_t(entry_bytes);
        const uint64_t type = tiff.get(e + 2, 2), n = tiff.get(e + 4, tiff.big ? 8 : 4);
        const uint64_t unit = type == 3 || type == 8 ? 2 : type == 4 || type == 9 || type == 11 || type == 13 ? 4
                              : type == 5 || type == 10 || type == 12 || type >= 16 ? 8 : 1;
        if (n <= (uint64_t(1) << 32) && n * unit > uint64_t(value_bytes))
            end = std::max(end, tiff.get(e + 4 + (tiff.big ? 8 : 4), value_bytes) + n * unit);
        switch (tiff.get(e, 2)) {
            case 256: if (!values(e, w)) return incomplete; break;
            case 257: if (!values(e, h)) return incomplete; break;
            case 259: if (!values(e, compression)) return incomplete; break;
            case 273: case 324: if (!values(e, offsets)) return incomplete; break;  // strip / tile offsets
            case 279: case 325: if (!values(e, counts)) return incomplete; break;   // byte counts
            default: break;
        }
    }
    if (w.size() != 1 || h.size() != 1 || w[0] != uint64_t(width) || h[0] != uint64_t(height)) return incomplete;
    if (offsets.empty() || offsets.size() != counts.size()) return incomplete;
    const bool deflate = compression[0] == 8 || compression[0] == 32946;
    for (size_t i = 0; i < offsets.size(); ++i) {
        if (offsets[i] > file.size() || counts[i] > file.size() - offsets[i]) return incomplete;
        if (deflate && !inflates_to_end(file, offsets[i], counts[i])) return incomplete;
        end = std::max(end, offsets[i] + counts[i]);
    }
    if (end != file.size()) return incomplete;
    return deflate ? Tiff::checked : Tiff::decode;
}

// OpenEXR (single part, scanline or single-level tiled): the header's attributes, then the
// offset table, then the chunks, each with its coordinates and its byte count. Every chunk
// must lie within the file and the last must end it (so a file cut short by one byte is
// found); ZIP and ZIPS chunks smaller than their raw pixels are zlib streams, inflated to
// their end (Adler-32). OpenImageIO then decodes every pixel (decodes_fully): a raw chunk
// has no check of its own, but its length is.
enum class Exr { incomplete, checked, decode };

Exr exr_completeness(const FileReader& file, int width, int height) {
    const Exr incomplete = Exr::incomplete;
    unsigned char head[8];
    if (!file.read(0, head, 8)) return incomplete;
    const TiffReader le{file, true, false};  // OpenEXR is little-endian
    const uint64_t version = le.get(head + 4, 4);
    const bool tiled = version & 0x200;
    if ((version & 0xff) != 2 || (version & 0x1800)) return Exr::decode;  // deep or multi-part: OpenImageIO alone
    int32_t box[4] = {0, 0, -1, -1};
    int compression = -1;
    uint64_t pixel_bytes = 0, tile_w = 0, tile_h = 0;
    int tile_mode = 0;
    uint64_t at = 8;
    // An attribute: name, type (NUL-terminated, at most 255 bytes each), int32 size, value.
    const auto text = [&](std::string& out) {
        out.clear();
        for (char c; out.size() < 256; out += c)
            if (!file.read(at++, &c, 1)) return false;
            else if (c == '\0') return true;
        return false;
    };
    for (std::string name, type;;) {
        if (!text(name)) return incomplete;
        if (name.empty()) break;  // the header's end
        unsigned char size_raw[4];
        if (!text(type) || !file.read(at, size_raw, 4)) return incomplete;
        const uint64_t size = le.get(size_raw, 4);
        at += 4;
        if (size > (uint64_t(1) << 24)) return incomplete;
        std::vector<unsigned char> value(static_cast<size_t>(size));
        if (!file.read(at, value.data(), value.size())) return incomplete;
        at += size;
        if (name == "dataWindow" && type == "box2i" && size == 16) {
            for (int i = 0; i < 4; ++i) box[i] = int32_t(uint32_t(le.get(value.data() + 4 * i, 4)));
        } else if (name == "compression" && size == 1) {
            compression = value[0];
        } else if (name == "tiles" && type == "tiledesc" && size == 9) {
            tile_w = le.get(value.data(), 4), tile_h = le.get(value.data() + 4, 4), tile_mode = value[8] & 0xf;
        } else if (name == "channels" && type == "chlist") {
            // name\0, int32 pixel type (0 uint, 1 half, 2 float), 12 more bytes; a NUL ends it.
            for (size_t i = 0; i < value.size() && value[i] != 0;) {
                while (i < value.size() && value[i] != 0) ++i;
                if (i + 17 > value.size()) return incomplete;
                pixel_bytes += le.get(value.data() + i + 1, 4) == 1 ? 2 : 4;
                i += 17;
            }
        }
    }
    if (int64_t(box[2]) - box[0] + 1 != width || int64_t(box[3]) - box[1] + 1 != height) return incomplete;
    if (tiled && (tile_w == 0 || tile_h == 0 || tile_mode != 0)) return Exr::decode;  // mipmaps: OpenImageIO alone
    // Scanlines per chunk (OpenEXR's compression methods: none, RLE, ZIPS, ZIP, PIZ, PXR24,
    // B44, B44A, DWAA, DWAB).
    static const int kLines[] = {1, 1, 1, 16, 32, 16, 32, 32, 32, 256};
    if (compression < 0 || compression > 9) return Exr::decode;
    const uint64_t lines = tiled ? tile_h : uint64_t(kLines[compression]);
    const uint64_t columns = tiled ? (uint64_t(width) + tile_w - 1) / tile_w : 1;
    const uint64_t chunks = columns * ((uint64_t(height) + lines - 1) / lines);
    if (chunks > (uint64_t(1) << 26)) return incomplete;
    std::vector<unsigned char> table(static_cast<size_t>(chunks) * 8);
    if (!file.read(at, table.data(), table.size())) return incomplete;
    const bool zip = compression == 2 || compression == 3;
    uint64_t end = 0;
    for (uint64_t c = 0; c < chunks; ++c) {
        const uint64_t offset = le.get(table.data() + 8 * c, 8);
        const uint64_t prefix = tiled ? 16 : 4;  // tile x, y, levels; or the first scanline
        unsigned char size_raw[4];
        if (!file.read(offset + prefix, size_raw, 4)) return incomplete;
        const uint64_t packed = le.get(size_raw, 4), data = offset + prefix + 4;
        if (data > file.size() || packed > file.size() - data) return incomplete;
        end = std::max(end, data + packed);
        // The chunk's raw size: its pixels (the last row or column of chunks may be short).
        const uint64_t cw = tiled ? std::min<uint64_t>(tile_w, uint64_t(width) - (c % columns) * tile_w) : uint64_t(width);
        const uint64_t ch = std::min<uint64_t>(lines, uint64_t(height) - (c / columns) * lines);
        if (zip && packed < cw * ch * pixel_bytes && !inflates_to_end(file, data, packed)) return incomplete;
    }
    return end == file.size() ? Exr::checked : incomplete;
}

}  // namespace

bool image_is_complete(const fs::path& path, int width, int height) {
    const FileReader file(path);
    unsigned char magic[4];
    if (!file.open() || !file.read(0, magic, 4)) return false;
    if (magic[0] == 0x89 && magic[1] == 'P' && magic[2] == 'N' && magic[3] == 'G') return png_is_complete(file, width, height);
    if ((magic[0] == 'I' && magic[1] == 'I') || (magic[0] == 'M' && magic[1] == 'M')) {
        switch (tiff_completeness(file, width, height)) {
            case Tiff::incomplete: return false;
            case Tiff::checked: return true;
            case Tiff::decode: break;
        }
    }
    if (magic[0] == 0x76 && magic[1] == 0x2f && magic[2] == 0x31 && magic[3] == 0x01 &&
        exr_completeness(file, width, height) == Exr::incomplete)
        return false;
    // Any other format (OpenEXR after the checks above): every pixel decoded, a band at a time.
    return image_codec().decodes_fully(path.string(), width, height);
}


}  // namespace tessera::io
