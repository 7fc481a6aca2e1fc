#include "raster/io/isolated_call.h"

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fcntl.h>

#include <atomic>
#include <cerrno>
#include <csignal>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <thread>

// Set by the sanitizer runtimes when present (libFuzzer registers its crash report there).
extern "C" void __sanitizer_set_death_callback(void (*callback)()) __attribute__((weak));

namespace tessera::io {
namespace {

// Exit codes of the child, beyond a signal.
enum ChildExit : int { kFinished = 0, kThrew = 3, kTimedOut = 4, kTooBig = 5, kPipe = 6 };

bool write_all(int fd, const void* data, size_t size) {
    const char* p = static_cast<const char*>(data);
    while (size > 0) {
        const ssize_t n = ::write(fd, p, size);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) return false;
        p += n;
        size -= size_t(n);
    }
    return true;
}

size_t resident_bytes() {
    // /proc/self/statm: size resident shared text lib data dt, in pages.
    FILE* f = std::fopen("/proc/self/statm", "r");
    if (!f) return 0;
    unsigned long size = 0, resident = 0;
    const int read = std::fscanf(f, "%lu %lu", &size, &resident);
    std::fclose(f);
    return read == 2 ? size_t(resident) * size_t(::sysconf(_SC_PAGESIZE)) : 0;
}

[[noreturn]] void child(int fd, const std::function<std::vector<uint8_t>()>& work, const IsolationLimits& limits) {
    // A crash is the child's way to fail: no core file, and none of the handlers the parent may
    // have installed (a sanitizer's or a fuzzer's, which would report it as their own finding).
    const rlimit no_core{0, 0};
    ::setrlimit(RLIMIT_CORE, &no_core);
    for (const int s : {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT}) std::signal(s, SIG_DFL);
    // A stop signal ends the child at once: the parent's handlers would clean up the parent's
    // files from the child's copy of its state, or (a polite stop) keep the child running. A
    // signal the parent ignores (SIGHUP under nohup) stays ignored.
    for (const int s : {SIGINT, SIGTERM, SIGHUP})
        if (std::signal(s, SIG_DFL) == SIG_IGN) std::signal(s, SIG_IGN);
    if (__sanitizer_set_death_callback) __sanitizer_set_death_callback(nullptr);
    const size_t baseline = resident_bytes();  // the parent's pages this child shares
    std::thread([&limits, baseline] {
        const auto start = std::chrono::steady_clock::now();
        while (true) {
            std::this_thread::sleep_for(std::chrono::milliseconds(10));
            if (std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() > limits.seconds)
                ::_exit(kTimedOut);
            const size_t resident = resident_bytes();
            if (resident > baseline && resident - baseline > limits.resident_bytes) ::_exit(kTooBig);
        }
    }).detach();
    std::vector<uint8_t> result;
    int code = kFinished;
    try {
        result = work();
    } catch (const std::exception& e) {
        const std::string message = e.what();
        result.assign(message.begin(), message.end());
        code = kThrew;
    } catch (...) {
        const std::string message = "an unknown exception";
        result.assign(message.begin(), message.end());
        code = kThrew;
    }
    ::_exit(write_all(fd, result.data(), result.size()) ? code : kPipe);
}

std::string signal_text(int signal) {
    const char* name = ::strsignal(signal);
    return "crashed with signal " + std::to_string(signal) + (name ? std::string(" (") + name + ")" : std::string());
}

}  // namespace

IsolatedResult run_isolated(const std::function<std::vector<uint8_t>()>& work, const IsolationLimits& limits) {
    IsolatedResult out;
    int fds[2];
    if (::pipe2(fds, O_CLOEXEC) != 0) {
        out.failure = std::string("cannot create a pipe: ") + std::strerror(errno);
        return out;
    }
    std::fflush(nullptr);  // nothing buffered is written twice
    const pid_t pid = ::fork();
    if (pid < 0) {
        out.failure = std::string("cannot start a process: ") + std::strerror(errno);
        ::close(fds[0]);
        ::close(fds[1]);
        return out;
    }
    if (pid == 0) {
        ::close(fds[0]);
        child(fds[1], work, limits);
    }
    ::close(fds[1]);
    char buffer[1 << 16];
    while (true) {
        const ssize_t n = ::read(fds[0], buffer, sizeof buffer);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) break;
        out.bytes.insert(out.bytes.end(), buffer, buffer + n);
    }
    ::close(fds[0]);
    int status = 0;
    while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
    if (WIFSIGNALED(status)) {
        out.failure = signal_text(WTERMSIG(status));
    } else if (!WIFEXITED(status)) {
        out.failure = "ended abnormally";
    } else {
        switch (WEXITSTATUS(status)) {
            case kFinished: out.ok = true; return out;
            case kThrew:
                out.threw = true;
                out.failure.assign(out.bytes.begin(), out.bytes.end());
                break;
            case kTimedOut: out.failure = "took longer than " + std::to_string(int(limits.seconds)) + " s"; break;
            case kTooBig:
                out.failure = "needed more than " + std::to_string(limits.resident_bytes >> 20) + " MiB of memory";
                break;
            case kPipe: out.failure = "could not hand back its result"; break;
            default: out.failure = "exited with status " + std::to_string(WEXITSTATUS(status)); break;
        }
    }
    out.bytes.clear();
    return out;
}

}  // namespace tessera::io
