#include "raster/io/header_check.h"

#include <cctype>
#include <charconv>
#include <cstdint>
#include <fstream>
#include <sstream>
#include <string_view>
#include <vector>

namespace tessera::io {
namespace {

// Headers are short; a longer one is not ours to judge.
constexpr size_t kHeaderBytes = 64 * 1024;

bool parse_count(const std::string& word, uint64_t& value) {
    const auto [end, ec] = std::from_chars(word.data(), word.data() + word.size(), value);
    return ec == std::errc() && end == word.data() + word.size();
}

// Saturating a * b + c on byte counts.
uint64_t add_product(uint64_t c, uint64_t a, uint64_t b) {
    constexpr uint64_t kMax = UINT64_MAX;
    if (a != 0 && b > kMax / a) return kMax;
    const uint64_t p = a * b;
    return p > kMax - c ? kMax : c + p;
}

int ply_type_bytes(const std::string& type) {
    static const std::pair<std::string_view, int> kTypes[] = {
        {"char", 1},  {"uchar", 1},  {"int8", 1},   {"uint8", 1},   {"short", 2},   {"ushort", 2},
        {"int16", 2}, {"uint16", 2}, {"int", 4},    {"uint", 4},    {"int32", 4},   {"uint32", 4},
        {"float", 4}, {"float32", 4}, {"double", 8}, {"float64", 8}};
    for (const auto& [name, bytes] : kTypes)
        if (type == name) return bytes;
    return 0;
}

std::string counted(uint64_t n, const std::string& what) { return std::to_string(n) + " " + what; }

// A word of the header as messages quote it: binary garbage shown as '?', at most 40 characters.
std::string shown(const std::string& word) {
    std::string out = word.substr(0, 40);
    for (char& c : out)
        if (!std::isprint(static_cast<unsigned char>(c))) c = '?';
    return "'" + out + (word.size() > 40 ? "...'" : "'");
}

// PLY: "element NAME COUNT" lines, each followed by its "property" lines, up to "end_header".
std::optional<std::string> check_ply(const std::string& head, uint64_t file_size) {
    std::istringstream lines(head);
    std::string line;
    bool ascii = true, ended = false;
    size_t number = 0;
    uint64_t need = 0;
    struct Element {
        std::string name;
        uint64_t count = 0, bytes = 0;
    };
    std::vector<Element> elements;
    size_t header_end = 0;
    while (std::getline(lines, line)) {
        header_end += line.size() + 1;
        ++number;
        std::istringstream words(line);
        std::string keyword;
        words >> keyword;
        if (number == 1 || keyword == "comment" || keyword == "obj_info") {
            continue;
        } else if (keyword == "format") {
            std::string format;
            words >> format;
            ascii = format == "ascii";
        } else if (keyword == "element") {
            Element e;
            std::string count;
            words >> e.name >> count;
            if (!parse_count(count, e.count))
                return "PLY header line " + std::to_string(number) + ": " + shown(count) + " is not an element count";
            elements.push_back(e);
        } else if (keyword == "property" && !elements.empty()) {
            std::string type;
            words >> type;
            if (type == "list") words >> type;  // the count's type: a list holds at least its count
            const int bytes = ply_type_bytes(type);
            if (bytes == 0) return "PLY header line " + std::to_string(number) + ": unknown property type " + shown(type);
            elements.back().bytes += ascii ? 2 : uint64_t(bytes);
        } else if (keyword == "end_header") {
            ended = true;
            break;
        }
        // Other lines are skipped, as Assimp does: some exporters wrote free text there.
    }
    if (!ended) return std::string("the PLY header has no end_header line in its first 64 KiB");
    for (const Element& e : elements) need = add_product(need, e.count, e.bytes);
    const uint64_t body = file_size > header_end ? file_size - header_end : 0;
    if (need <= body) return std::nullopt;
    std::string list;
    for (const Element& e : elements) list += (list.empty() ? "" : ", ") + counted(e.count, shown(e.name));
    return "the PLY header declares " + list + " elements, more than the file's " + std::to_string(body) +
           " bytes of data can hold";
}

// OFF: an "OFF" line (with optional ST/C/N/4/n prefixes), comments, then "V F E".
std::optional<std::string> check_off(const std::string& head, uint64_t file_size) {
    std::istringstream lines(head);
    std::string line;
    bool keyword = false;
    while (std::getline(lines, line)) {
        const size_t hash = line.find('#');
        if (hash != std::string::npos) line.resize(hash);
        std::istringstream words(line);
        std::string first;
        if (!(words >> first)) continue;
        if (!keyword) {
            keyword = true;
            if (first.size() >= 3 && first.compare(first.size() - 3, 3, "OFF") == 0) {
                if (!(words >> first)) continue;  // counts on the next line
            }
        }
        std::string second;
        uint64_t vertices = 0, faces = 0;
        if (!(words >> second) || !parse_count(first, vertices) || !parse_count(second, faces)) return std::nullopt;
        // At least "0 0 0\n" per vertex and "0\n" per face.
        const uint64_t need = add_product(add_product(0, vertices, 6), faces, 2);
        if (need <= file_size) return std::nullopt;
        return "the OFF header declares " + counted(vertices, "vertices") + " and " + counted(faces, "faces") +
               ", more than the file's " + std::to_string(file_size) + " bytes can hold";
    }
    return std::nullopt;
}

}  // namespace

std::optional<std::string> header_problem(const std::filesystem::path& path) {
    std::error_code ec;
    const uintmax_t size = std::filesystem::file_size(path, ec);
    if (ec) return std::nullopt;
    std::ifstream in(path, std::ios::binary);
    std::string head(kHeaderBytes, '\0');
    in.read(head.data(), std::streamsize(head.size()));
    head.resize(size_t(in.gcount()));
    // As Assimp recognises the format: by extension, or by the first bytes of the file.
    std::string ext = path.extension().string();
    for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
    std::istringstream first_line(head.substr(0, head.find('\n')));
    std::string magic;
    first_line >> magic;
    // OBJ is text: a NUL byte in its first 64 KiB means binary data (a wrong file, a corrupt
    // or sparse one), which Assimp would read to its end, however large, as an empty mesh.
    if (ext == ".obj")
        if (const size_t nul = head.find('\0'); nul != std::string::npos)
            return "not an OBJ text file (binary data at byte " + std::to_string(nul) + ")";
    if (ext == ".ply" || head.compare(0, 3, "ply") == 0) return check_ply(head, size);
    if (ext == ".off" || (magic.size() >= 3 && magic.size() <= 8 && magic.compare(magic.size() - 3, 3, "OFF") == 0))
        return check_off(head, size);
    return std::nullopt;
}

}  // namespace tessera::io
