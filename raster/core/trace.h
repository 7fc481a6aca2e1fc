// A Chrome trace-event recorder (opens in Perfetto or chrome://tracing): one track per thread
// that worked, one slice per stage, per tile and per frame, so the critical loops can be seen
// on a timeline. When no trace is active a TraceScope costs one atomic load.
//
// Usage:  Trace trace; trace.activate();  ... { TraceScope s("raster"); ... }  ...
//         trace.deactivate(); trace.write("frame.json");
#pragma once
#include <atomic>
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>

namespace tessera {

// Wall milliseconds since `start`: how the stages time themselves for --stats.
using Clock = std::chrono::steady_clock;
inline double ms_since(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

class Trace {
public:
    Trace();
    ~Trace();
    Trace(const Trace&) = delete;
    Trace& operator=(const Trace&) = delete;

    // Makes this the trace that TraceScopes record into (one at a time per process).
    void activate();
    void deactivate();
    static Trace* active() { return active_.load(std::memory_order_acquire); }

    // A complete slice on the calling thread's track. `name` and `category` must be string
    // literals (they are stored as pointers). arg_x/arg_y are shown as slice arguments when
    // not negative (a tile's coordinates, a frame number).
    void record(const char* name, const char* category, int64_t begin_ns, int64_t end_ns,
                int arg_x = -1, int arg_y = -1);

    size_t event_count() const;

    // Writes {"traceEvents": [...]} with thread-name metadata, atomically.
    void write(const std::filesystem::path& path) const;

    static int64_t now_ns() {
        return std::chrono::duration_cast<std::chrono::nanoseconds>(
                   std::chrono::steady_clock::now().time_since_epoch())
            .count();
    }

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
    static std::atomic<Trace*> active_;
};

// Records a slice from construction to destruction into the active trace, if any.
class TraceScope {
public:
    explicit TraceScope(const char* name, const char* category = "stage", int arg_x = -1,
                        int arg_y = -1)
        : trace_(Trace::active()), name_(name), category_(category), x_(arg_x), y_(arg_y),
          begin_(trace_ ? Trace::now_ns() : 0) {}
    ~TraceScope() {
        if (trace_) trace_->record(name_, category_, begin_, Trace::now_ns(), x_, y_);
    }
    TraceScope(const TraceScope&) = delete;
    TraceScope& operator=(const TraceScope&) = delete;

private:
    Trace* trace_;
    const char* name_;
    const char* category_;
    int x_, y_;
    int64_t begin_;
};

}  // namespace tessera
