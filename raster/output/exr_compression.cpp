#include "raster/output/exr_compression.h"

#include <stdexcept>
#include <string>

namespace tessera::output {

ExrCompression parse_exr_compression(std::string_view name) {
    for (const ExrCompression c : {ExrCompression::none, ExrCompression::zip, ExrCompression::piz, ExrCompression::dwaa})
        if (name == exr_compression_name(c)) return c;
    throw std::invalid_argument("--exr: unknown compression '" + std::string(name) +
                                "' (expected zip, piz, dwaa or none)");
}

const char* exr_compression_name(ExrCompression compression) {
    switch (compression) {
        case ExrCompression::none: return "none";
        case ExrCompression::zip: return "zip";
        case ExrCompression::piz: return "piz";
        case ExrCompression::dwaa: return "dwaa";
    }
    return "zip";
}

}  // namespace tessera::output
