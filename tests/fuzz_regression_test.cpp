// Replays every file of tests/fuzz/corpus/<target>/ (the seeds and every input a fuzzer ever
// crashed or broke a property with) through the fuzz targets of tests/fuzz/, built with the
// default compiler: a fixed bug stays fixed even where clang and libFuzzer are not installed.
// Under the "sanitize" preset the same replay runs with ASan and UBSan.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <vector>

#include "tests/fuzz/fuzz_target.h"

namespace tessera::fuzz {
namespace {

namespace fs = std::filesystem;

std::vector<uint8_t> read_bytes(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Runs `target` on each corpus file of `name`; returns how many there were.
size_t replay(const char* name, std::string (*target)(Bytes)) {
    const fs::path dir = fs::path(TESSERA_FUZZ_CORPUS) / name;
    std::vector<fs::path> files;
    for (const auto& entry : fs::directory_iterator(dir))
        if (entry.is_regular_file()) files.push_back(entry.path());
    std::sort(files.begin(), files.end());
    for (const fs::path& file : files) {
        const std::vector<uint8_t> bytes = read_bytes(file);
        EXPECT_EQ(target(bytes), "") << file.filename();
    }
    return files.size();
}

// Each corpus must hold seeds, or the replay proves nothing.
TEST(FuzzRegression, ObjCorpus) { EXPECT_GT(replay("obj", obj_input), 5u); }
TEST(FuzzRegression, SceneCorpus) { EXPECT_GT(replay("scene", scene_input), 5u); }
TEST(FuzzRegression, ImageCorpus) { EXPECT_GT(replay("image", image_input), 5u); }
TEST(FuzzRegression, RasterCorpus) { EXPECT_GT(replay("raster", raster_input), 5u); }
TEST(FuzzRegression, ModelCorpus) { EXPECT_GT(replay("model", model_input), 5u); }

}  // namespace
}  // namespace tessera::fuzz
