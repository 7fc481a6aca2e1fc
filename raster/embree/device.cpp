#include "raster/embree/device.h"

#include <xmmintrin.h>

#include "raster/core/error.h"

namespace tessera::embree {
namespace {

// MXCSR bit 15 is flush-to-zero, bit 6 denormals-are-zero (Intel SDM vol. 1, 10.2.3).
constexpr unsigned kFlushToZero = 0x8000u;
constexpr unsigned kDenormalsAreZero = 0x0040u;

const char* error_name(RTCError code) {
    switch (code) {
        case RTC_ERROR_NONE: return "no error";
        case RTC_ERROR_INVALID_ARGUMENT: return "invalid argument";
        case RTC_ERROR_INVALID_OPERATION: return "invalid operation";
        case RTC_ERROR_OUT_OF_MEMORY: return "out of memory";
        case RTC_ERROR_UNSUPPORTED_CPU: return "unsupported CPU";
        case RTC_ERROR_CANCELLED: return "cancelled";
        default: return "unknown error";
    }
}

}  // namespace

FlushDenormals::FlushDenormals() : saved_(_mm_getcsr()) {
    _mm_setcsr(saved_ | kFlushToZero | kDenormalsAreZero);
}

FlushDenormals::~FlushDenormals() { _mm_setcsr(saved_); }

bool denormals_flushed() {
    const unsigned csr = _mm_getcsr();
    return (csr & kFlushToZero) && (csr & kDenormalsAreZero);
}

RayDevice::RayDevice(const std::string& config) {
    device_ = rtcNewDevice(config.empty() ? nullptr : config.c_str());
    if (!device_)
        throw Error(std::string("embree: cannot create a device: ") +
                    error_name(rtcGetDeviceError(nullptr)));
    rtcSetDeviceErrorFunction(device_, &RayDevice::on_error, this);
}

RayDevice::~RayDevice() { rtcReleaseDevice(device_); }

void RayDevice::on_error(void* self, RTCError code, const char* message) {
    auto* device = static_cast<RayDevice*>(self);
    const std::lock_guard lock(device->mutex_);
    if (device->first_error_.empty())
        device->first_error_ = std::string(error_name(code)) + (message ? ": " : "") +
                               (message ? message : "");
}

void RayDevice::check(const char* what) const {
    // rtcGetDeviceError also clears Embree's own per-thread error code.
    const RTCError code = rtcGetDeviceError(device_);
    std::string message;
    {
        const std::lock_guard lock(mutex_);
        message.swap(first_error_);
    }
    if (message.empty() && code != RTC_ERROR_NONE) message = error_name(code);
    if (!message.empty()) throw Error(std::string("embree: ") + what + ": " + message);
}

bool RayDevice::native_packet16() const {
    return rtcGetDeviceProperty(device_, RTC_DEVICE_PROPERTY_NATIVE_RAY16_SUPPORTED) != 0;
}

bool RayDevice::shares_tbb() const {
    return rtcGetDeviceProperty(device_, RTC_DEVICE_PROPERTY_TASKING_SYSTEM) == 1;
}

const RayDevice& default_ray_device() {
    static const RayDevice device;
    return device;
}

}  // namespace tessera::embree
