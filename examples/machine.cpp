#include "examples/machine.h"

#include <fstream>

namespace tessera::cli {

std::string cpu_model() {
    std::ifstream cpuinfo("/proc/cpuinfo");
    for (std::string line; std::getline(cpuinfo, line);)
        if (line.rfind("model name", 0) == 0) {
            const auto colon = line.find(':');
            if (colon != std::string::npos) return line.substr(colon + 2);
        }
    return "unknown";
}

const char* simd_target() {
#if defined(__AVX512F__)
    return "AVX-512 (16 float lanes)";
#elif defined(__AVX2__)
    return "AVX2 (8 float lanes)";
#else
    return "scalar fallback";
#endif
}

}  // namespace tessera::cli
