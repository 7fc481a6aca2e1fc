#include "examples/signals.h"

#include <csignal>
#include <cstring>

#include "raster/core/atomic_file.h"

namespace tessera::cli {
namespace {

constexpr int kSignals[] = {SIGINT, SIGTERM, SIGHUP};
volatile std::sig_atomic_t g_stop_signal = 0;

// Installs `handler` for the three signals; a SIGHUP ignored at start (nohup) is left alone.
void install(void (*handler)(int)) {
    for (const int s : kSignals) {
        struct sigaction current {};
        sigaction(s, nullptr, &current);
        if (s == SIGHUP && current.sa_handler == SIG_IGN) continue;
        struct sigaction action {};
        action.sa_handler = handler;
        sigemptyset(&action.sa_mask);
        sigaction(s, &action, nullptr);
    }
}

// Only async-signal-safe calls from here on (POSIX.1 signal-safety(7)): unlink(2) through
// remove_unfinished_temporaries, sigaction(2), raise(3).
extern "C" void end_now(int signal) {
    remove_unfinished_temporaries();
    struct sigaction fallback {};
    fallback.sa_handler = SIG_DFL;
    sigemptyset(&fallback.sa_mask);
    sigaction(signal, &fallback, nullptr);
    raise(signal);  // dies of the signal, as without a handler: the exit status says which
}

extern "C" void record_stop(int signal) {
    g_stop_signal = signal;
    install(end_now);  // a second signal does not wait for the frame
}

}  // namespace

void end_cleanly_on_signals() { install(end_now); }

StopRequest::StopRequest() {
    g_stop_signal = 0;
    install(record_stop);
}

StopRequest::~StopRequest() { install(end_now); }

int StopRequest::signal() const { return g_stop_signal; }

std::string signal_name(int signal) {
    switch (signal) {
        case SIGINT: return "SIGINT";
        case SIGTERM: return "SIGTERM";
        case SIGHUP: return "SIGHUP";
        default: return "signal " + std::to_string(signal);
    }
}

}  // namespace tessera::cli
