// The Embree device: one per process is enough (it owns no threads of its own here, see
// below), shared by every ray scene.
//
// Errors: Embree reports through a C callback, which must not throw (it runs inside Embree's
// C++ code compiled without our exception contract). The callback records the first error
// message; RayDevice::check() turns it into a tessera::Error ("embree: ...") at the points
// where tessera can fail cleanly (after creating geometry, after committing a scene).
//
// Threads: Debian's Embree is built on oneTBB, so its BVH builds run in the same TBB arena as
// the rasterizer's tiles. The device is created without a "threads=" setting on purpose: that
// setting makes Embree install its own process-wide tbb::global_control, which would override
// the --threads cap the command installed. Tracing calls run on whatever TBB worker calls them.
//
// Denormals: Embree recommends FTZ and DAZ "for each thread before calling rtcIntersect or
// rtcOccluded" (api.md, Performance Recommendations). TBB workers copy the FP settings of the
// thread that created the arena, which may be long before a device exists, so every task that
// traces sets them itself with FlushDenormals (and restores them, so rasterizer code that runs
// later on the same worker computes exactly what it computes everywhere else).
#pragma once
#include <embree3/rtcore.h>

#include <mutex>
#include <string>

namespace tessera::embree {

// Sets MXCSR flush-to-zero and denormals-are-zero for the current thread while alive.
class FlushDenormals {
public:
    FlushDenormals();
    ~FlushDenormals();
    FlushDenormals(const FlushDenormals&) = delete;
    FlushDenormals& operator=(const FlushDenormals&) = delete;

private:
    unsigned saved_;
};

// True when the current thread has both FTZ and DAZ set (for tests and the device banner).
bool denormals_flushed();

class RayDevice {
public:
    // `config` is Embree's device configuration string (e.g. "verbose=1"); never "threads=".
    explicit RayDevice(const std::string& config = "");
    ~RayDevice();
    RayDevice(const RayDevice&) = delete;
    RayDevice& operator=(const RayDevice&) = delete;

    RTCDevice handle() const { return device_; }

    // Throws tessera::Error with the first error Embree reported since the last check
    // (through the callback or rtcGetDeviceError), then forgets it.
    void check(const char* what) const;

    // Whether this build of Embree traces 16-wide packets natively (AVX-512) rather than
    // splitting them into two 8-wide halves.
    bool native_packet16() const;

    // Whether Embree schedules its BVH builds on oneTBB (RTC_DEVICE_PROPERTY_TASKING_SYSTEM
    // 1), i.e. in the same thread pool as tessera's tiles rather than threads of its own.
    bool shares_tbb() const;

private:
    static void on_error(void* self, RTCError code, const char* message);

    RTCDevice device_ = nullptr;
    mutable std::mutex mutex_;
    mutable std::string first_error_;
};

// The process's default device, created on first use (thread-safe).
const RayDevice& default_ray_device();

}  // namespace tessera::embree
