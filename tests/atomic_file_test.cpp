// write_file_atomically clears temporaries that killed writers left beside the target
// (issue 10: an animation killed with SIGKILL and resumed ends with no debris), and keeps
// those of live processes; a signal handler can remove those of the files being written.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <span>
#include <string>
#include <vector>

#include "raster/core/atomic_file.h"

namespace tessera {
namespace {

namespace fs = std::filesystem;

TEST(AtomicFile, RemovesTemporariesOfDeadWritersOnly) {
    const fs::path dir = fs::temp_directory_path() / ("tessera_atomic_" + std::to_string(getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    // pid_max is at most 2^22 on Linux, so this pid is never alive.
    const fs::path dead = dir / ".f_0001.png.tmp2147483000_3";
    const fs::path live = dir / (".f_0001.png.tmp" + std::to_string(getpid()) + "_999");
    const fs::path other = dir / ".f_0002.png.tmp2147483000_4";  // another frame's: not ours to judge
    for (const fs::path& p : {dead, live, other}) std::ofstream(p) << "partial";
    write_file_atomically(dir / "f_0001.png", "complete");
    EXPECT_FALSE(fs::exists(dead));
    EXPECT_TRUE(fs::exists(live));
    EXPECT_TRUE(fs::exists(other));
    std::ifstream in(dir / "f_0001.png");
    std::string text;
    in >> text;
    EXPECT_EQ(text, "complete");
    fs::remove_all(dir);
}

// What a signal handler does before the process dies (examples/signals.h): the temporary of
// a file being written goes, the finished files stay. Run in a child that then ends without
// unwinding (no destructor may tidy up for it).
TEST(AtomicFile, UnfinishedTemporariesGoOnRequest) {
    const fs::path dir = fs::temp_directory_path() / ("tessera_atomic_signal_" + std::to_string(getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    const pid_t child = fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
        write_file_atomically(dir / "done.txt", "complete");
        AtomicFile open(dir / "frame.exr");
        const std::string half = "half a frame";
        open.write_at(0, std::as_bytes(std::span(half.data(), half.size())));
        remove_unfinished_temporaries();
        _exit(0);
    }
    int status = 0;
    ASSERT_EQ(waitpid(child, &status, 0), child);
    ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
    EXPECT_EQ(names, std::vector<std::string>{"done.txt"});
    fs::remove_all(dir);
}

}  // namespace
}  // namespace tessera
