#include "examples/resident_memory.h"

#include <malloc.h>

#include <cstddef>
#include <fstream>
#include <string>

// GCC says __SANITIZE_ADDRESS__ / __SANITIZE_THREAD__, clang __has_feature.
#if defined(__SANITIZE_ADDRESS__)
#define TESSERA_SANITIZER_ALLOCATOR "AddressSanitizer"
#elif defined(__SANITIZE_THREAD__)
#define TESSERA_SANITIZER_ALLOCATOR "ThreadSanitizer"
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define TESSERA_SANITIZER_ALLOCATOR "AddressSanitizer"
#elif __has_feature(thread_sanitizer)
#define TESSERA_SANITIZER_ALLOCATOR "ThreadSanitizer"
#endif
#endif
#ifdef TESSERA_SANITIZER_ALLOCATOR
// Declared here rather than through <sanitizer/allocator_interface.h>, which clang ships and
// GCC does not; both compilers' ASan and TSan runtimes export the function.
extern "C" size_t __sanitizer_get_current_allocated_bytes();
#endif

namespace tessera::cli {
namespace {

// The value of a "Key:   1234 kB" line of /proc/self/status, in MiB.
double status_mib(const std::string& key) {
    std::ifstream status("/proc/self/status");
    std::string line;
    while (std::getline(status, line))
        if (line.compare(0, key.size(), key) == 0 && line.size() > key.size() && line[key.size()] == ':')
            return std::stod(line.substr(key.size() + 1)) / 1024.0;
    return 0.0;
}

}  // namespace

double resident_mib() { return status_mib("VmRSS"); }
double peak_resident_mib() { return status_mib("VmHWM"); }

bool reset_peak_resident() {
    std::ofstream clear("/proc/self/clear_refs");
    clear << "5";
    clear.flush();
    return bool(clear);
}

double heap_mib() {
#ifdef TESSERA_SANITIZER_ALLOCATOR
    return double(__sanitizer_get_current_allocated_bytes()) / (1024.0 * 1024.0);
#else
    const struct mallinfo2 info = mallinfo2();
    return double(info.uordblks + info.hblkhd) / (1024.0 * 1024.0);
#endif
}

const char* sanitizer_allocator() {
#ifdef TESSERA_SANITIZER_ALLOCATOR
    return TESSERA_SANITIZER_ALLOCATOR;
#else
    return nullptr;
#endif
}

}  // namespace tessera::cli
