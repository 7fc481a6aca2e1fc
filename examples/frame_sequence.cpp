#include "examples/frame_sequence.h"

#include <charconv>
#include <stdexcept>

namespace tessera {

namespace {

bool parse_int(std::string_view text, int& value) {
    if (text.empty()) return false;
    const char* end = text.data() + text.size();
    auto [ptr, ec] = std::from_chars(text.data(), end, value);
    return ec == std::errc() && ptr == end;
}

}  // namespace

FrameRange parse_frame_range(const std::string& text) {
    const auto colon = text.find(':');
    FrameRange range;
    const std::string_view all(text);
    const bool ok = colon == std::string::npos
                        ? parse_int(all, range.first) && (range.last = range.first, true)
                        : parse_int(all.substr(0, colon), range.first) &&
                              parse_int(all.substr(colon + 1), range.last);
    if (!ok)
        throw std::invalid_argument("--frames expects A:B or N with integers, got '" + text + "'");
    if (range.first < 0 || range.last < 0)
        throw std::invalid_argument("--frames '" + text + "': frame numbers must not be negative");
    if (range.last < range.first)
        throw std::invalid_argument("--frames '" + text + "' is reversed: the range is inclusive, "
                                    "first:last with first <= last");
    return range;
}

Shard parse_shard(const std::string& text) {
    const auto slash = text.find('/');
    Shard shard;
    const std::string_view all(text);
    if (slash == std::string::npos || !parse_int(all.substr(0, slash), shard.index) ||
        !parse_int(all.substr(slash + 1), shard.count))
        throw std::invalid_argument("--shard expects I/N, got '" + text + "'");
    if (shard.count < 1 || shard.index < 0 || shard.index >= shard.count)
        throw std::invalid_argument("--shard '" + text + "': need 0 <= I < N");
    return shard;
}

std::vector<int> frames_of_shard(const FrameRange& range, const Shard& shard) {
    std::vector<int> frames;
    for (long long f = range.first + shard.index; f <= range.last; f += shard.count)
        frames.push_back(int(f));
    return frames;
}

FramePattern::FramePattern(std::string pattern) : text_(std::move(pattern)) {
    const auto hash = text_.find('#');
    const auto percent = text_.find('%');
    if (hash != std::string::npos) {
        size_t end = hash;
        while (end < text_.size() && text_[end] == '#') ++end;
        if (text_.find('#', end) != std::string::npos || percent != std::string::npos)
            throw std::invalid_argument("output pattern '" + text_ +
                                        "' has more than one frame placeholder");
        prefix_ = text_.substr(0, hash);
        suffix_ = text_.substr(end);
        width_ = int(end - hash);
    } else if (percent != std::string::npos) {
        // %d or %0Nd (N up to 9): the only printf conversions a frame number needs.
        size_t i = percent + 1;
        int width = 0;
        if (i < text_.size() && text_[i] == '0') {
            ++i;
            if (i < text_.size() && text_[i] >= '1' && text_[i] <= '9') width = text_[i++] - '0';
            else i = text_.size();  // "%0" with no width: malformed
        }
        if (i >= text_.size() || text_[i] != 'd' || text_.find('%', i) != std::string::npos)
            throw std::invalid_argument("output pattern '" + text_ +
                                        "': use '####' or '%04d' for the frame number");
        prefix_ = text_.substr(0, percent);
        suffix_ = text_.substr(i + 1);
        width_ = width;
    }
}

std::filesystem::path FramePattern::fixed_directory() const {
    // The folders before the placeholder's component (before the file name, without one).
    const std::string& before = width_ < 0 ? text_ : prefix_;
    const size_t slash = before.rfind('/');
    if (slash == std::string::npos) return ".";
    return slash == 0 ? std::string("/") : before.substr(0, slash);
}

std::filesystem::path FramePattern::path_for(int frame) const {
    if (width_ < 0) return text_;
    std::string digits = std::to_string(frame);
    if (int(digits.size()) < width_) digits.insert(0, size_t(width_) - digits.size(), '0');
    return prefix_ + digits + suffix_;
}

}  // namespace tessera
