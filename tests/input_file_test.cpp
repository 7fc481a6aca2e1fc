// Input that is not what it claims to be (issue 19), in process: every reader (scene files,
// OBJ meshes, model files, images, camera files) refuses at once what is not a regular file
// (a directory, a device, a FIFO that would block, a symlink to a device), names the file,
// and refuses a sparse file of gigabytes without reading it; a JSON key given twice is found
// with its pointer. (tests/cli_input_files.sh checks the command's side: exit 1, the value's
// JSON Pointer, nothing written.)
#include "raster/core/input_file.h"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include "raster/core/camera.h"
#include "raster/core/error.h"
#include "raster/io/camera_file.h"
#include "raster/io/image_io.h"
#include "raster/io/model_file.h"
#include "raster/io/obj_loader.h"
#include "raster/scene_file/json_reader.h"
#include "raster/scene_file/scene_file_error.h"
#include "raster/scene_file/scene_parse.h"

namespace fs = std::filesystem;
using namespace tessera;

namespace {

struct InputFiles : ::testing::Test {
    fs::path dir = fs::temp_directory_path() / ("tessera_input_files_" + std::to_string(getpid()));
    void SetUp() override {
        fs::remove_all(dir);
        fs::create_directories(dir / "folder.obj");
        ASSERT_EQ(mkfifo((dir / "fifo.obj").c_str(), 0600), 0);
        fs::create_symlink("/dev/zero", dir / "zero.obj");
        std::ofstream(dir / "sparse.obj").close();
        fs::resize_file(dir / "sparse.obj", uint64_t(8) << 30);  // 8 GiB of holes: nothing is stored
    }
    void TearDown() override { fs::remove_all(dir); }
};

// The message of the tessera::Error `read` throws ("" if it throws none).
std::string error_of(const std::function<void()>& read) {
    try {
        read();
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

#define EXPECT_REFUSED(call, words) \
    do { \
        const std::string message = error_of([&] { (void)(call); }); \
        EXPECT_NE(message.find(words), std::string::npos) << #call << ": '" << message << "'"; \
    } while (0)

}  // namespace

TEST_F(InputFiles, WhatIsNotARegularFileIsRefusedAtOnce) {
    const fs::path fifo = dir / "fifo.obj", folder = dir / "folder.obj", zero = dir / "zero.obj";
    for (const fs::path& p : {fs::path("/dev/zero"), fs::path("/dev/urandom"), fifo, zero}) {
        EXPECT_REFUSED(InputFile(p), "not a regular file");
        EXPECT_REFUSED(io::load_obj(p), "not a regular file");
        EXPECT_REFUSED(io::read_model(p), "not a regular file");
        EXPECT_REFUSED(io::read_image(p), "not a regular file");
        Camera camera;
        EXPECT_REFUSED(io::read_camera_file(p, camera), "not a regular file");
        std::vector<std::string> warnings;
        EXPECT_REFUSED(scene_file::load_scene_file(p, warnings), "not a regular file");
    }
    EXPECT_REFUSED(InputFile(folder), "it is a directory");
    EXPECT_REFUSED(io::load_obj(folder), "it is a directory");
    EXPECT_REFUSED(io::read_model(folder), "it is a directory");
    EXPECT_REFUSED(io::read_image(folder), "it is a directory");
    EXPECT_REFUSED(InputFile(dir / "missing.obj"), "no such file");
    EXPECT_REFUSED(io::read_image(fifo), fifo.string());  // the file is named
}

TEST_F(InputFiles, ASparseFileOfGigabytesIsRefusedWithoutReadingIt) {
    const fs::path sparse = dir / "sparse.obj";
    EXPECT_REFUSED(io::load_obj(sparse), "binary data at byte 0");
    EXPECT_REFUSED(io::read_model(sparse), "binary data at byte 0");
    std::vector<std::string> warnings;
    EXPECT_REFUSED(scene_file::load_scene_file(sparse, warnings), "a scene file at most 64 MiB");
}

TEST_F(InputFiles, ARegularFileIsReadWhole) {
    const fs::path p = dir / "text.txt";
    std::ofstream(p) << "v 0 0 0\n";
    InputFile file(p);
    EXPECT_EQ(file.size(), 8u);
    EXPECT_EQ(file.read(3), "v 0");
    EXPECT_EQ(file.read_rest(), " 0 0\n");
}

TEST(RepeatedKeys, EachRepeatIsFoundWithItsPointer) {
    EXPECT_EQ(scene_file::repeated_keys(R"({"objects": [], "materials": {"m": {"kd": 1, "kd": 2}},
                                            "objects": [{"a": 1}, {"a": 1, "b~/": 2, "b~/": 3}]})"),
              (std::vector<std::string>{"/materials/m/kd", "/objects", "/objects/1/b~0~1"}));
    EXPECT_TRUE(scene_file::repeated_keys(R"({"a": {"x": 1}, "b": {"x": 1}, "c": [{"x": 1}, {"x": 2}]})").empty());
}
