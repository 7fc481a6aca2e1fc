// Where a frame's tile stage spends its time, pass by pass, for --stats.
//
// Each pass of each tile is timed with the steady clock (wall time of the thread running the
// tile) and the times are summed over the frame's tiles, so they are thread time: on N threads
// they add up to about N times the stage's wall time. `tiles_ms` is the same sum over whole
// tiles (every pass plus what lies between them: gathering and resolving multisampled
// layers), so the passes never add up to more than it. The toon outlines run over the finished
// frame, after the tiles, in blocks of rows: each block's time counts as the outline pass's
// and as a whole tile's. Timing is on only when the caller asks for stats: without, a tile
// pays one null test per pass.
#pragma once
#include <array>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <string_view>

namespace tessera::render {

enum class TilePass {
    shade,        // the opaque surfaces' shading kernel
    background,   // the environment (colour, sky, cube map) behind them
    transparent,  // finding the transparent triangles in front (alpha test included)
    shadows,      // shadow rays or shadow-map lookups, and the shadowed pixels shaded again
    blend,        // the transparent triangles shaded and blended
    terrain,      // ray-marched height fields
    metaballs,    // ray-marched metaballs
    fog,          // fog over what is drawn
    outline,      // toon outlines over the finished frame (after the tiles, by rows)
};
inline constexpr size_t kTilePasses = 9;

std::string_view tile_pass_name(TilePass pass);

// One frame's sums, in milliseconds of thread time.
struct TilePassTimes {
    std::array<double, kTilePasses> ms{};
    double tiles_ms = 0;  // whole tiles; >= the sum of ms

    double operator[](TilePass p) const { return ms[size_t(p)]; }
    double passes_ms() const;
};

// The running sums a frame's tiles add to, from any thread.
class TilePassClock {
public:
    using Clock = std::chrono::steady_clock;

    void add(TilePass pass, Clock::duration d) { pass_ns_[size_t(pass)].fetch_add(d.count(), std::memory_order_relaxed); }
    void add_tile(Clock::duration d) { tile_ns_.fetch_add(d.count(), std::memory_order_relaxed); }
    void reset();
    TilePassTimes times() const;

private:
    std::array<std::atomic<Clock::rep>, kTilePasses> pass_ns_{};
    std::atomic<Clock::rep> tile_ns_{0};
};

// Times its scope into `clock` as `pass`; does nothing (no clock read) when clock is null.
class TimedPass {
public:
    TimedPass(TilePassClock* clock, TilePass pass) : clock_(clock), pass_(pass) {
        if (clock_) start_ = TilePassClock::Clock::now();
    }
    ~TimedPass() {
        if (clock_) clock_->add(pass_, TilePassClock::Clock::now() - start_);
    }
    TimedPass(const TimedPass&) = delete;
    TimedPass& operator=(const TimedPass&) = delete;

private:
    TilePassClock* clock_;
    TilePass pass_;
    TilePassClock::Clock::time_point start_;
};

// Times its scope into `clock` as a whole tile; nothing when clock is null.
class TimedTile {
public:
    explicit TimedTile(TilePassClock* clock) : clock_(clock) {
        if (clock_) start_ = TilePassClock::Clock::now();
    }
    ~TimedTile() {
        if (clock_) clock_->add_tile(TilePassClock::Clock::now() - start_);
    }
    TimedTile(const TimedTile&) = delete;
    TimedTile& operator=(const TimedTile&) = delete;

private:
    TilePassClock* clock_;
    TilePassClock::Clock::time_point start_;
};

}  // namespace tessera::render
