#include "raster/io/image_codec.h"

#include <dlfcn.h>

#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "raster/core/error.h"

namespace tessera::io {
namespace fs = std::filesystem;

namespace {

constexpr const char* kModuleFile = "libtessera_image_codec.so";

// TESSERA_IMAGE_CODEC when set (a program moved away from its build or packaged elsewhere),
// and only it; otherwise next to the running program (every program of the build is in its
// bin/), then where the build put the module.
std::vector<fs::path> module_candidates() {
    std::vector<fs::path> paths;
    if (const char* chosen = std::getenv("TESSERA_IMAGE_CODEC"); chosen && *chosen) return {fs::path(chosen)};
    std::error_code error;
    const fs::path program = fs::read_symlink("/proc/self/exe", error);
    if (!error) paths.push_back(program.parent_path() / kModuleFile);
    const fs::path built = TESSERA_IMAGE_CODEC_BUILT;
    if (paths.empty() || built != paths.front()) paths.push_back(built);
    return paths;
}

const ImageCodec& load_codec() {
    std::string reasons;
    for (const fs::path& path : module_candidates()) {
        std::error_code error;
        if (!fs::is_regular_file(path, error)) {
            reasons += (reasons.empty() ? "" : "; ") + path.string() + ": no such file";
            continue;
        }
        // RTLD_LOCAL: OpenImageIO's hundreds of symbols stay out of the program's namespace.
        void* module = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
        if (!module) {
            const char* why = dlerror();
            reasons += (reasons.empty() ? "" : "; ") + path.string() + ": " + (why ? why : "dlopen failed");
            continue;
        }
        const auto entry = reinterpret_cast<ImageCodecEntry>(dlsym(module, TESSERA_IMAGE_CODEC_ENTRY));
        const ImageCodec* codec = entry ? entry() : nullptr;
        if (!codec || codec->abi != ImageCodec::kAbi) {
            reasons += (reasons.empty() ? "" : "; ") + path.string() + ": not this version's image codec (rebuild tessera)";
            dlclose(module);
            continue;
        }
        return *codec;  // the module stays loaded for the life of the process
    }
    throw Error("cannot load the image codec " + std::string(kModuleFile) +
                " (OpenImageIO, which reads and writes EXR, TIFF and image textures): " + reasons);
}

}  // namespace

const ImageCodec& image_codec() {
    static const ImageCodec& codec = load_codec();  // a failed load throws, and is tried again
    return codec;
}

}  // namespace tessera::io
