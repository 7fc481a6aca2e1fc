#include "raster/core/trace.h"

#include <tbb/enumerable_thread_specific.h>

#include <algorithm>
#include <cstdio>
#include <mutex>
#include <thread>
#include <vector>

#include "raster/core/atomic_file.h"

namespace tessera {

std::atomic<Trace*> Trace::active_{nullptr};

namespace {

struct Event {
    const char* name;
    const char* category;
    int64_t begin_ns;
    int64_t end_ns;
    int arg_x, arg_y;
};

// Track ids are small integers in the order threads first recorded (thread ids are not
// stable across runs, track numbers are); the activating thread's track is named "main".
struct Track {
    int id = -1;
    bool main = false;  // the thread that activated the trace
    std::vector<Event> events;
};

}  // namespace

struct Trace::Impl {
    tbb::enumerable_thread_specific<Track> tracks;
    std::atomic<int> next_track{0};
    int64_t origin_ns = Trace::now_ns();
    std::thread::id owner = std::this_thread::get_id();
};

Trace::Trace() : impl_(std::make_unique<Impl>()) {}

Trace::~Trace() {
    Trace* self = this;
    active_.compare_exchange_strong(self, nullptr);
}

void Trace::activate() {
    impl_->owner = std::this_thread::get_id();
    active_.store(this);
}

void Trace::deactivate() {
    Trace* self = this;
    active_.compare_exchange_strong(self, nullptr);
}

void Trace::record(const char* name, const char* category, int64_t begin_ns, int64_t end_ns,
                   int arg_x, int arg_y) {
    Track& track = impl_->tracks.local();
    if (track.id < 0) {
        track.id = impl_->next_track.fetch_add(1);
        track.main = std::this_thread::get_id() == impl_->owner;
    }
    track.events.push_back({name, category, begin_ns, end_ns, arg_x, arg_y});
}

size_t Trace::event_count() const {
    size_t n = 0;
    for (const Track& track : impl_->tracks) n += track.events.size();
    return n;
}

void Trace::write(const std::filesystem::path& path) const {
    std::vector<const Track*> tracks;
    for (const Track& track : impl_->tracks)
        if (track.id >= 0) tracks.push_back(&track);
    std::sort(tracks.begin(), tracks.end(),
              [](const Track* a, const Track* b) { return a->id < b->id; });

    std::string json = "{\"displayTimeUnit\":\"ms\",\"traceEvents\":[\n";
    char line[256];
    bool first = true;
    auto append = [&](int n) {
        if (!first) json += ",\n";
        first = false;
        json.append(line, size_t(std::min(n, int(sizeof line) - 1)));
    };
    append(std::snprintf(line, sizeof line,
                         R"({"name":"process_name","ph":"M","pid":1,"tid":0,"args":{"name":"tessera"}})"));
    for (const Track* track : tracks) {
        const int tid = track->id + 1;
        if (track->main)
            append(std::snprintf(line, sizeof line,
                                 R"({"name":"thread_name","ph":"M","pid":1,"tid":%d,"args":{"name":"main"}})",
                                 tid));
        else
            append(std::snprintf(line, sizeof line,
                                 R"({"name":"thread_name","ph":"M","pid":1,"tid":%d,"args":{"name":"worker %d"}})",
                                 tid, tid));
        for (const Event& e : track->events) {
            // Complete events ("X") in microseconds relative to the trace's creation.
            const double ts = double(e.begin_ns - impl_->origin_ns) * 1e-3;
            const double dur = double(e.end_ns - e.begin_ns) * 1e-3;
            if (e.arg_x >= 0 && e.arg_y >= 0)
                append(std::snprintf(line, sizeof line,
                                     R"({"name":"%s","cat":"%s","ph":"X","pid":1,"tid":%d,"ts":%.3f,"dur":%.3f,"args":{"x":%d,"y":%d}})",
                                     e.name, e.category, tid, ts, dur, e.arg_x, e.arg_y));
            else if (e.arg_x >= 0)
                append(std::snprintf(line, sizeof line,
                                     R"({"name":"%s","cat":"%s","ph":"X","pid":1,"tid":%d,"ts":%.3f,"dur":%.3f,"args":{"n":%d}})",
                                     e.name, e.category, tid, ts, dur, e.arg_x));
            else
                append(std::snprintf(line, sizeof line,
                                     R"({"name":"%s","cat":"%s","ph":"X","pid":1,"tid":%d,"ts":%.3f,"dur":%.3f})",
                                     e.name, e.category, tid, ts, dur));
        }
    }
    json += "\n]}\n";
    write_file_atomically(path, json);
}

}  // namespace tessera
