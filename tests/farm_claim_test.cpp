// Frame claims (raster/farm/frame_claim.h): exclusive creation, respect for live claims,
// takeover of dead or expired ones only when allowed, and release of only one's own claim.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>

#include "examples/farm/frame_claim.h"

namespace tessera::farm {
namespace {

namespace fs = std::filesystem;

struct ClaimTest : ::testing::Test {
    fs::path dir = fs::temp_directory_path() / ("tessera_claim_" + std::to_string(getpid()));
    fs::path frame = dir / "f_0001.png";
    void SetUp() override { fs::create_directories(dir); }
    void TearDown() override { fs::remove_all(dir); }
    void write_claim(const std::string& text) { std::ofstream(claim_path(frame)) << text; }
    std::string read_claim() {
        std::ifstream in(claim_path(frame));
        return std::string(std::istreambuf_iterator<char>(in), {});
    }
};

TEST(ClaimOwner, TextRoundTripsAndRejectsGarbage) {
    const ClaimOwner o{"node17", 4242, 1700000000};
    const auto back = ClaimOwner::parse(o.text());
    ASSERT_TRUE(back);
    EXPECT_EQ(back->host, "node17");
    EXPECT_EQ(back->pid, 4242);
    EXPECT_EQ(back->time, 1700000000);
    EXPECT_FALSE(ClaimOwner::parse(""));
    EXPECT_FALSE(ClaimOwner::parse("node17 notapid 5"));
    EXPECT_FALSE(ClaimOwner::parse("node17 0 5"));
}

TEST(ClaimOwner, StaleOnlyWhenAllowedAndDeadOrOld) {
    const ClaimOwner self = current_owner();
    ClaimPolicy respect;
    ClaimPolicy take{true, 0.0};
    ClaimPolicy take_old{true, 60.0};
    const ClaimOwner alive{self.host, int64_t(getppid()), self.time};
    const ClaimOwner elsewhere{"some-other-host", 1, self.time - 3600};
    EXPECT_FALSE(claim_is_stale(alive, self, take));
    EXPECT_FALSE(claim_is_stale(elsewhere, self, take));  // another host's pid says nothing here
    EXPECT_TRUE(claim_is_stale(elsewhere, self, take_old));
    EXPECT_FALSE(claim_is_stale(elsewhere, self, respect));
}

TEST_F(ClaimTest, FirstClaimWinsSecondIsHeld) {
    EXPECT_EQ(try_claim(frame, {}), ClaimResult::claimed);
    EXPECT_EQ(claim_path(frame), dir / ".f_0001.png.claim");
    const auto owner = ClaimOwner::parse(read_claim());
    ASSERT_TRUE(owner);
    EXPECT_EQ(owner->pid, getpid());
    EXPECT_EQ(try_claim(frame, {true, 0.0}), ClaimResult::held);  // ours and alive: not stale
    release_claim(frame);
    EXPECT_FALSE(fs::exists(claim_path(frame)));
    EXPECT_EQ(try_claim(frame, {}), ClaimResult::claimed);
}

TEST_F(ClaimTest, ReleaseLeavesOthersClaims) {
    write_claim("some-other-host 77 1\n");
    release_claim(frame);
    EXPECT_TRUE(fs::exists(claim_path(frame)));
}

TEST_F(ClaimTest, ExpiredClaimIsTakenOverOnlyWithPolicy) {
    write_claim("some-other-host 77 1\n");  // made in 1970
    EXPECT_EQ(try_claim(frame, {false, 60.0}), ClaimResult::held);
    EXPECT_EQ(try_claim(frame, {true, 0.0}), ClaimResult::held);  // age alone needs a timeout
    EXPECT_EQ(try_claim(frame, {true, 60.0}), ClaimResult::taken_over);
    EXPECT_EQ(ClaimOwner::parse(read_claim())->pid, getpid());
    // No renamed leftovers of the stale claim.
    int files = 0;
    for (const auto& e : fs::directory_iterator(dir)) files += e.is_regular_file();
    EXPECT_EQ(files, 1);
}

TEST_F(ClaimTest, EmptyClaimBeingWrittenIsHeld) {
    write_claim("");
    EXPECT_EQ(try_claim(frame, {true, 1.0}), ClaimResult::held);
}

// What a process killed between creating and writing its claim leaves (empty), or garbage,
// or a folder in the claim's place: judged by its age, never held for ever.
TEST_F(ClaimTest, UnreadableClaimsAreTakenOverByTheirAge) {
    const auto age = [&](double seconds) {
        fs::last_write_time(claim_path(frame), fs::file_time_type::clock::now() -
                                                   std::chrono::duration_cast<fs::file_time_type::duration>(
                                                       std::chrono::duration<double>(seconds)));
    };
    for (const std::string& text : {std::string(), std::string("\x01garbage"), std::string("host only")}) {
        write_claim(text);
        age(30.0);
        EXPECT_EQ(try_claim(frame, {false, 0.0}), ClaimResult::held) << "without --resume: respected";
        EXPECT_EQ(try_claim(frame, {true, 0.0}), ClaimResult::held) << "younger than a minute";
        EXPECT_EQ(try_claim(frame, {true, 3600.0}), ClaimResult::held) << "younger than --claim-timeout";
        EXPECT_EQ(try_claim(frame, {true, 10.0}), ClaimResult::taken_over) << "older than --claim-timeout";
        EXPECT_TRUE(ClaimOwner::parse(read_claim())) << "now ours";
        release_claim(frame);
        write_claim(text);
        age(kUnreadableClaimAge + 5.0);
        EXPECT_EQ(try_claim(frame, {true, 0.0}), ClaimResult::taken_over) << "older than a minute";
        release_claim(frame);
    }
    fs::create_directory(claim_path(frame));
    age(kUnreadableClaimAge + 5.0);
    EXPECT_EQ(try_claim(frame, {true, 0.0}), ClaimResult::taken_over);
    EXPECT_TRUE(fs::is_regular_file(claim_path(frame)));
    release_claim(frame);
    EXPECT_TRUE(fs::is_empty(dir)) << "the folder that stood in the claim's place is gone";
}

// A claimer killed at any instant (SIGKILL: no handler runs) leaves no claim or a whole one
// that names it, never an empty one that would hold the frame until its age broke it. A child
// claims and releases the frame in a loop; it is killed after a varying delay, and the claim
// file is read: hundreds of kills land at every point of try_claim.
TEST_F(ClaimTest, KilledClaimerLeavesNoEmptyClaim) {
    int partial = 0, whole = 0;
    for (int i = 0; i < 200; ++i) {
        const pid_t child = fork();
        ASSERT_GE(child, 0);
        if (child == 0) {
            for (;;) {
                try {
                    if (try_claim(frame, {}) != ClaimResult::held) release_claim(frame);
                } catch (...) {
                }
            }
        }
        usleep(useconds_t(200 + (i * 37) % 700));
        kill(child, SIGKILL);
        int status = 0;
        waitpid(child, &status, 0);
        const fs::path claim = claim_path(frame);
        if (fs::exists(claim)) {
            const std::optional<ClaimOwner> owner = ClaimOwner::parse(read_claim());
            if (owner && owner->pid == int64_t(child)) ++whole;
            else ++partial;
            fs::remove(claim);
        }
        for (const auto& entry : fs::directory_iterator(dir)) fs::remove(entry.path());  // its temporaries
    }
    EXPECT_EQ(partial, 0) << "claims left empty or naming another process (and " << whole << " whole ones)";
}

TEST_F(ClaimTest, UnwritableFolderThrows) {
    EXPECT_THROW(try_claim(dir / "missing" / "f.png", {}), std::runtime_error);
}

}  // namespace
}  // namespace tessera::farm
