// Runs a piece of work in a child process (fork) and hands its result back as bytes, so that a
// crash, an endless loop or a runaway allocation inside third-party code (Assimp's parsers, on
// a malformed file) ends the child, not tessera: the caller gets a one-line reason instead.
//
// The child runs `work` on its only thread while a watchdog thread checks its wall time and
// resident memory every 10 ms and ends it past either limit; it leaves with _exit, so nothing
// of the parent's (buffers, atexit handlers, the sanitizers' exit checks) runs twice. The
// result travels through a pipe, read while the child writes. The work must not use the
// parent's threads (oneTBB): only the forking thread exists in the child.
#pragma once
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace tessera::io {

struct IsolationLimits {
    double seconds = 10.0;
    size_t resident_bytes = size_t(2) << 30;
};

// What the child produced: its bytes when it finished (`ok`), else why it did not ("crashed
// with signal 11 (Segmentation fault)", "took longer than 10 s", "needed more than 2048 MiB
// of memory"). `work` may throw: the exception's message comes back as the failure.
struct IsolatedResult {
    bool ok = false;
    bool threw = false;  // the failure is the message of an exception `work` threw
    std::vector<uint8_t> bytes;
    std::string failure;
};

IsolatedResult run_isolated(const std::function<std::vector<uint8_t>()>& work, const IsolationLimits& limits);

}  // namespace tessera::io
