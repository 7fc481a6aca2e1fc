// Fuzz target: image files read as textures (raster/texture/texture.h through
// raster/image_io.h's read_image) and TSID visibility files (raster/visibility_io.h).
// The first byte picks the format (file extension), the rest is the file. Accepted images
// must give a texture whose mip chain ends at 1x1 with the documented level sizes; accepted
// TSID files must hold exactly width*height ids (times the sample count when multisampled).
#include <unistd.h>

#include <array>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#if defined(__SANITIZE_ADDRESS__)  // gcc -fsanitize=address
#define TESSERA_HAVE_LSAN 1
#elif defined(__has_feature)  // clang
#if __has_feature(address_sanitizer)
#define TESSERA_HAVE_LSAN 1
#endif
#endif
#ifdef TESSERA_HAVE_LSAN
#include <sanitizer/lsan_interface.h>
#endif

#include "raster/core/error.h"
#include "raster/io/image_io.h"
#include "raster/texture/texture.h"
#include "raster/io/visibility_io.h"
#include "tests/fuzz/fuzz_target.h"

namespace tessera::fuzz {
namespace {

// Formats whose readers OpenImageIO takes from Debian's libraries (libpng, libtiff, its own
// PFM/PNM/HDR/BMP/TGA readers), plus our TSID. EXR is left out: OpenEXR 3.1's header parser
// allocates what the file's attribute sizes claim (1.7 GB from a few hundred bytes, found
// here), inside the library and before OpenImageIO returns a size tessera could check.
constexpr std::array<const char*, 8> kExtensions = {".png", ".pfm", ".tif", ".ppm", ".hdr", ".bmp", ".tga", ".tsid"};

// OpenImageIO 2.4's PNG reader leaks a std::string when libpng longjmps out of its read
// callback on a truncated file (PNGInput::PngReadCallback -> ImageInput::geterror: the
// destructor is jumped over). That is Debian's library, not tessera, so allocations made
// while OpenImageIO decodes are not counted as leaks; everything after it (the texture and
// its mip chain) still is.
io::FloatImage read_image_outside_leak_check(const std::filesystem::path& path) {
#ifdef TESSERA_HAVE_LSAN
    __lsan::ScopedDisabler not_ours;
#endif
    return io::read_image(path);
}

// A per-process scratch file (fuzzers and ctest may run in parallel).
std::filesystem::path scratch_file(const char* extension) {
    return std::filesystem::temp_directory_path() /
           ("tessera_fuzz_image_" + std::to_string(getpid()) + extension);
}

std::string check_texture(const texture::Texture& t) {
    int w = t.width(), h = t.height();
    for (int k = 0; k < t.level_count(); ++k) {
        const texture::MipLevel& level = t.level(k);
        if (level.width != w || level.height != h) return "mip level " + std::to_string(k) + " has the wrong size";
        if (level.texels.size() != size_t(w) * size_t(h)) return "mip level texel count is wrong";
        w = std::max(1, w / 2);
        h = std::max(1, h / 2);
    }
    const texture::MipLevel& last = t.level(t.level_count() - 1);
    if (last.width != 1 || last.height != 1) return "mip chain does not end at 1x1";
    return "";
}

}  // namespace

std::string image_input(Bytes data) {
    if (data.empty()) return "";
    const char* extension = kExtensions[data[0] % kExtensions.size()];
    const std::filesystem::path path = scratch_file(extension);
    {
        std::ofstream out(path, std::ios::binary | std::ios::trunc);
        out.write(reinterpret_cast<const char*>(data.data() + 1), std::streamsize(data.size() - 1));
    }
    std::string broken;
    try {
        if (std::string(extension) == ".tsid") {
            const VisibilityBuffer v = io::read_tsid(path);
            if (v.width < 1 || v.height < 1 || v.triangle.size() != size_t(v.width) * size_t(v.height) ||
                v.sample_triangle.size() != (v.samples > 1 ? v.triangle.size() * size_t(v.samples) : 0))
                broken = "TSID accepted with inconsistent size";
        } else {
            // load_texture(path, encoding), with the decoding outside the leak check.
            const io::FloatImage image = read_image_outside_leak_check(path);
            broken = check_texture(texture::Texture::from_image(
                image, data.size() > 1 && data[1] % 2 ? texture::TexelEncoding::linear : texture::TexelEncoding::srgb));
        }
    } catch (const Error&) {
    } catch (const std::invalid_argument&) {
    }
    std::error_code ec;
    std::filesystem::remove(path, ec);
    return broken;
}

}  // namespace tessera::fuzz

TESSERA_FUZZ_ENTRY(image_input)
