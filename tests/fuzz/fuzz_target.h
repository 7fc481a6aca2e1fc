// Fuzz targets: one file per loader or stage (tests/fuzz/fuzz_*.cpp), each a function from
// arbitrary bytes to a verdict. The same functions are built two ways:
// - with clang and libFuzzer (`make fuzz`, preset "fuzz"): TESSERA_LIBFUZZER is defined and
//   TESSERA_FUZZ_ENTRY turns the function into LLVMFuzzerTestOneInput, aborting on a broken
//   property so libFuzzer keeps the input;
// - with the default compiler into tessera_tests, where fuzz_regression_test.cpp feeds every
//   file of tests/fuzz/corpus/<target>/ (seeds and past crashers) through them, so a
//   regression is caught without clang.
//
// Rejecting an input with tessera::Error, SceneFileError or std::invalid_argument is the
// expected outcome for bad bytes; a crash, a sanitizer report, any other exception or a
// returned message (a property that does not hold) is a finding.
#pragma once
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>

namespace tessera::fuzz {

using Bytes = std::span<const uint8_t>;

// Each returns "" when every property held, else what broke (one line).
std::string obj_input(Bytes data);     // fuzz_obj.cpp: the OBJ loader
std::string scene_input(Bytes data);   // fuzz_scene.cpp: the JSON scene reader
std::string image_input(Bytes data);   // fuzz_image.cpp: image files as textures, TSID files
std::string raster_input(Bytes data);  // fuzz_raster.cpp: tile rasterizer vs scalar reference
std::string model_input(Bytes data);   // fuzz_model.cpp: the model importer (Assimp, isolated)

}  // namespace tessera::fuzz

#ifdef TESSERA_LIBFUZZER
#include <cstdio>
#include <cstdlib>
#define TESSERA_FUZZ_ENTRY(function)                                                   \
    extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {          \
        const std::string broken = tessera::fuzz::function({data, size});             \
        if (!broken.empty()) {                                                         \
            std::fprintf(stderr, "fuzz property broken: %s\n", broken.c_str());        \
            std::abort();                                                              \
        }                                                                              \
        return 0;                                                                      \
    }
#else
#define TESSERA_FUZZ_ENTRY(function)
#endif
