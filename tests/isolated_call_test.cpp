// io::run_isolated (raster/io/isolated_call.h), which keeps third-party parsers' crashes,
// endless loops and runaway allocations out of tessera: each outcome comes back as a result.
#include <gtest/gtest.h>

#include <csignal>
#include <stdexcept>
#include <string>
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

// The child does not run the parent's handlers for stop signals (tessera's clean-up or its
// polite stop of `render`): SIGTERM ends it, SIGHUP ignored by the parent stays ignored.
TEST(IsolatedCall, StopSignalsEndTheChildNotTheParentsHandlers) {
    static volatile std::sig_atomic_t handled = 0;
    const auto term = std::signal(SIGTERM, [](int) { handled = 1; });
    const auto hup = std::signal(SIGHUP, SIG_IGN);
    const IsolatedResult terminated = run_isolated([]() -> std::vector<uint8_t> {
        std::raise(SIGTERM);
        return {uint8_t(handled)};
    }, quick());
    const IsolatedResult hung_up = run_isolated([]() -> std::vector<uint8_t> {
        std::raise(SIGHUP);
        return {7};
    }, quick());
    std::signal(SIGTERM, term);
    std::signal(SIGHUP, hup);
    EXPECT_FALSE(terminated.ok);
    EXPECT_NE(terminated.failure.find("signal " + std::to_string(SIGTERM)), std::string::npos) << terminated.failure;
    ASSERT_TRUE(hung_up.ok) << hung_up.failure;
    EXPECT_EQ(hung_up.bytes, std::vector<uint8_t>{7});
    EXPECT_EQ(handled, 0);
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
