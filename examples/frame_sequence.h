// Which frames a render produces and what each file is called: the inclusive frame range
// ("--frames A:B", as Blender's -s/-e), the farm shard ("--shard I/N"), and the output
// pattern ("out/snakes_####.png" or "out/snakes_%04d.png").
#pragma once
#include <filesystem>
#include <string>
#include <vector>

namespace tessera {

struct FrameRange {
    int first = 1;
    int last = 1;  // inclusive
    int count() const { return last - first + 1; }
};

// "A:B" (inclusive, 0 <= A <= B) or a single frame "N". Throws std::invalid_argument.
FrameRange parse_frame_range(const std::string& text);

// A slice of a frame range for a farm: shard `index` of `count` renders the frames at
// positions index, index + count, index + 2*count, ... of the range (0-based, so a scheduler's
// array task id 0..N-1 maps directly). Shards are disjoint and cover the range.
struct Shard {
    int index = 0;
    int count = 1;
};

// "I/N" with 0 <= I < N. Throws std::invalid_argument.
Shard parse_shard(const std::string& text);

std::vector<int> frames_of_shard(const FrameRange& range, const Shard& shard);

// An output path with a frame-number placeholder: a run of '#' (zero-padded to its length)
// or a printf-style "%d"/"%0Nd". A pattern without a placeholder is only valid for a
// single frame (otherwise every frame would overwrite the last).
class FramePattern {
public:
    // Throws std::invalid_argument for two placeholders or a malformed printf field.
    explicit FramePattern(std::string pattern);

    bool has_placeholder() const { return width_ >= 0; }
    std::filesystem::path path_for(int frame) const;
    const std::string& text() const { return text_; }
    // The deepest folder of the pattern without the placeholder, where files the frames share
    // go: "out" for "out/f_####.png" and for "out/####/beauty.png", "." for "f_####.png".
    std::filesystem::path fixed_directory() const;

private:
    std::string text_;
    std::string prefix_, suffix_;
    int width_ = -1;  // digits to pad to; -1 when the pattern has no placeholder
};

}  // namespace tessera
