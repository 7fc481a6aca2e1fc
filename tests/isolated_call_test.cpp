// io::run_isolated (raster/io/isolated_call.h), which keeps third-party parsers' crashes,
// endless loops and runaway allocations out of tessera: each outcome comes back as a result.
#include <gtest/gtest.h>

#include <csignal>
#include <stdexcept>
#include <vector>

#include "raster/io/isolated_call.h"

namespace tessera::io {
namespace {

IsolationLimits quick() {
    IsolationLimits limits;
    limits.seconds = 0.5;
    limits.resident_bytes = size_t(256) << 20;
    return limits;
}

TEST(IsolatedCall, HandsBackTheBytes) {
    std::vector<uint8_t> big(300000);  // more than a pipe holds: read while the child writes
    for (size_t i = 0; i < big.size(); ++i) big[i] = uint8_t(i * 7);
    const IsolatedResult r = run_isolated([&] { return big; }, quick());
    ASSERT_TRUE(r.ok) << r.failure;
    EXPECT_EQ(r.bytes, big);
}

TEST(IsolatedCall, AnExceptionIsItsMessage) {
    const IsolatedResult r = run_isolated([]() -> std::vector<uint8_t> { throw std::runtime_error("bad header"); },
                                          quick());
    EXPECT_FALSE(r.ok);
    EXPECT_TRUE(r.threw);
    EXPECT_EQ(r.failure, "bad header");
}

TEST(IsolatedCall, ACrashIsReportedNotShared) {
    const IsolatedResult r = run_isolated([]() -> std::vector<uint8_t> {
        std::raise(SIGSEGV);
        return {};
    }, quick());
    EXPECT_FALSE(r.ok);
    EXPECT_FALSE(r.threw);
    EXPECT_NE(r.failure.find("signal 11"), std::string::npos) << r.failure;
    EXPECT_TRUE(r.bytes.empty());
}

TEST(IsolatedCall, AnEndlessLoopTimesOut) {
    const IsolatedResult r = run_isolated([]() -> std::vector<uint8_t> {
        volatile bool forever = true;
        while (forever) {
        }
        return {};
    }, quick());
    EXPECT_FALSE(r.ok);
    EXPECT_NE(r.failure.find("took longer than"), std::string::npos) << r.failure;
}

TEST(IsolatedCall, ARunawayAllocationIsStopped) {
    IsolationLimits limits;
    limits.seconds = 60.0;  // the memory limit, not the clock, must end it
    limits.resident_bytes = size_t(64) << 20;
    const IsolatedResult r = run_isolated([]() -> std::vector<uint8_t> {
        std::vector<std::vector<uint8_t>> hog;
        while (true) hog.emplace_back(size_t(16) << 20, uint8_t(1));  // touched, so resident
    }, limits);
    EXPECT_FALSE(r.ok);
    EXPECT_NE(r.failure.find("MiB of memory"), std::string::npos) << r.failure;
}

}  // namespace
}  // namespace tessera::io
