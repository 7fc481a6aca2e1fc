// A one-line progress bar for long runs (done/total, rate per second, elapsed, ETA), redrawn in place with '\r' on stderr when stderr is a
// terminal and silent otherwise (logs and pipes get no control characters). No Debian package
// offers one for C++, so it is this small class.
#pragma once
#include <chrono>
#include <cstdint>
#include <string>

namespace tessera::cli {

class Progress {
public:
    // `unit` names what is counted ("steps"); total > 0.
    Progress(std::string label, int64_t total, std::string unit);
    ~Progress();
    // Records that `done` of total are finished; redraws at most ten times a second.
    void update(int64_t done);
    // Draws 100% and ends the line.
    void finish();

private:
    void draw(int64_t done);
    std::string label_, unit_;
    int64_t total_;
    bool enabled_;
    bool finished_ = false;
    std::chrono::steady_clock::time_point start_, last_draw_;
};

}  // namespace tessera::cli
