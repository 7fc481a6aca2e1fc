// `tessera info`: what this build and this machine offer (SIMD width, cores, libraries). Every
// benchmark report starts from these facts, so they are printed the same way everywhere.
#include <embree3/rtcore.h>
#include <tbb/info.h>

#include <cstdio>
#include <string>
#include <thread>

#include "examples/command.h"
#include "examples/machine.h"
#include "examples/resident_memory.h"

namespace tessera::cli {
namespace {

Run define_info(CLI::App& root) {
    root.add_subcommand("info", "print the build's SIMD target, cores and libraries");
    return [] {
        std::printf("cpu: %s\n", cpu_model().c_str());
        std::printf("hardware threads: %u (oneTBB default concurrency %d)\n",
                    std::thread::hardware_concurrency(), tbb::info::default_concurrency());
        std::printf("simd: %s\n", simd_target());
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
