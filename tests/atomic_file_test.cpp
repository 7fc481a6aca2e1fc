// write_file_atomically clears temporaries that killed writers left beside the target
// (issue 10: an animation killed with SIGKILL and resumed ends with no debris), and keeps
// those of live processes.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

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

}  // namespace
}  // namespace tessera
