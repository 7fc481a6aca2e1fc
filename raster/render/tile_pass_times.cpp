#include "raster/render/tile_pass_times.h"

namespace tessera::render {

std::string_view tile_pass_name(TilePass pass) {
    switch (pass) {
        case TilePass::shade: return "shade";
        case TilePass::background: return "background";
        case TilePass::transparent: return "transparent";
        case TilePass::shadows: return "shadows";
        case TilePass::blend: return "blend";
        case TilePass::terrain: return "terrain";
        case TilePass::metaballs: return "metaballs";
        case TilePass::fog: return "fog";
        case TilePass::outline: return "outline";
    }
    return "?";
}

double TilePassTimes::passes_ms() const {
    double sum = 0;
    for (double m : ms) sum += m;
    return sum;
}

void TilePassClock::reset() {
    for (auto& ns : pass_ns_) ns.store(0, std::memory_order_relaxed);
    tile_ns_.store(0, std::memory_order_relaxed);
}

TilePassTimes TilePassClock::times() const {
    constexpr double kMs = 1e-6;
    static_assert(std::is_same_v<TilePassClock::Clock::period, std::nano>, "the sums are kept in nanoseconds");
    TilePassTimes t;
    for (size_t p = 0; p < kTilePasses; ++p) t.ms[p] = double(pass_ns_[p].load(std::memory_order_relaxed)) * kMs;
    t.tiles_ms = double(tile_ns_.load(std::memory_order_relaxed)) * kMs;
    return t;
}

}  // namespace tessera::render
