#include "examples/progress.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>

namespace tessera::cli {

Progress::Progress(std::string label, int64_t total, std::string unit)
    : label_(std::move(label)), unit_(std::move(unit)), total_(std::max<int64_t>(total, 1)),
      enabled_(isatty(fileno(stderr)) != 0), start_(std::chrono::steady_clock::now()),
      last_draw_(start_) {}

Progress::~Progress() {
    if (enabled_ && !finished_) std::fputc('\n', stderr);  // leave the cursor on a fresh line
}

void Progress::update(int64_t done) {
    if (!enabled_) return;
    const auto now = std::chrono::steady_clock::now();
    if (now - last_draw_ < std::chrono::milliseconds(100)) return;
    last_draw_ = now;
    draw(done);
}

void Progress::finish() {
    if (!enabled_ || finished_) return;
    draw(total_);
    std::fputc('\n', stderr);
    finished_ = true;
}

void Progress::draw(int64_t done) {
    constexpr int kWidth = 30;
    const double fraction = std::clamp(double(done) / double(total_), 0.0, 1.0);
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    const double eta = fraction > 0 ? elapsed * (1 - fraction) / fraction : 0;
    const int filled = int(fraction * kWidth);
    std::string bar(size_t(filled), '#');
    bar.resize(kWidth, ' ');
    const double rate = elapsed > 0 ? double(done) / elapsed : 0.0;
    // "\033[K" clears what a longer previous line left to the right.
    std::fprintf(stderr, "\r%s [%s] %3d%% %lld/%lld %s, %.2f %s/s, %.1fs elapsed, ETA %.1fs\033[K", label_.c_str(),
                 bar.c_str(), int(fraction * 100), static_cast<long long>(done),
                 static_cast<long long>(total_), unit_.c_str(), rate, unit_.c_str(), elapsed, eta);
    std::fflush(stderr);
}

}  // namespace tessera::cli
