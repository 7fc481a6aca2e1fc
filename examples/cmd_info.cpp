// `tessera info`: what this build and this machine offer (SIMD width, cores, libraries). Every
// benchmark report starts from these facts, so they are printed the same way everywhere.
#include <embree3/rtcore.h>
#include <tbb/info.h>

#include <cstdio>
#include <fstream>
#include <string>
#include <thread>

#include "examples/command.h"
#include "examples/resident_memory.h"

namespace tessera::cli {
namespace {

std::string cpu_model() {
    std::ifstream cpuinfo("/proc/cpuinfo");
    for (std::string line; std::getline(cpuinfo, line);)
        if (line.rfind("model name", 0) == 0) {
            const auto colon = line.find(':');
            if (colon != std::string::npos) return line.substr(colon + 2);
        }
    return "unknown";
}

Run define_info(CLI::App& root) {
    root.add_subcommand("info", "print the build's SIMD target, cores and libraries");
    return [] {
        std::printf("cpu: %s\n", cpu_model().c_str());
        std::printf("hardware threads: %u (oneTBB default concurrency %d)\n",
                    std::thread::hardware_concurrency(), tbb::info::default_concurrency());
#if defined(__AVX512F__)
        std::printf("simd: AVX-512 (16 float lanes)\n");
#elif defined(__AVX2__)
        std::printf("simd: AVX2 (8 float lanes)\n");
#else
        std::printf("simd: scalar fallback\n");
#endif
        RTCDevice device = rtcNewDevice(nullptr);
        if (device) {
            std::printf("embree: %s, native ISA %s\n", RTC_VERSION_STRING,
                        rtcGetDeviceProperty(device, RTC_DEVICE_PROPERTY_NATIVE_RAY16_SUPPORTED)
                            ? "with 16-wide packets"
                            : "without 16-wide packets");
            rtcReleaseDevice(device);
        }
        if (const char* sanitizer = sanitizer_allocator())
            std::printf("sanitizer: %s (its allocator and shadow memory count in the resident set)\n", sanitizer);
        return 0;
    };
}

TESSERA_COMMAND(90, define_info);

}  // namespace
}  // namespace tessera::cli
