#include "oracle/embree_handles.h"

#include <pmmintrin.h>
#include <xmmintrin.h>

#include <cstdio>
#include <cstdlib>

#include "core/error.h"

namespace so {

static void onEmbreeError(void*, RTCError code, const char* str) {
    // Any Embree error means the scene or a query is not what we think: stop rather than report a
    // ground truth that may be wrong.
    std::fprintf(stderr, "internal error: Embree error %d: %s\n", int(code), str ? str : "");
    std::abort();
}

EmbreeDevice::EmbreeDevice(const std::string& config) {
    device_ = rtcNewDevice(config.empty() ? nullptr : config.c_str());
    if (!device_) {
        std::fprintf(stderr, "internal error: cannot create Embree device (error %d)\n",
                     int(rtcGetDeviceError(nullptr)));
        std::abort();
    }
    // Set right after creation so that no error is missed.
    rtcSetDeviceErrorFunction(device_, onEmbreeError, nullptr);
    // Masks are compiled into Debian's Embree; the oracle relies on them being honoured.
    SO_CHECK(rtcGetDeviceProperty(device_, RTC_DEVICE_PROPERTY_RAY_MASK_SUPPORTED) == 1);
}

EmbreeDevice::~EmbreeDevice() {
    if (device_) rtcReleaseDevice(device_);
}

std::string EmbreeDevice::version() {
    return std::to_string(RTC_VERSION_MAJOR) + "." + std::to_string(RTC_VERSION_MINOR) + "." +
           std::to_string(RTC_VERSION_PATCH);
}

EmbreeScene::EmbreeScene(const EmbreeDevice& device) : scene_(rtcNewScene(device.get())) {
    SO_CHECK(scene_ != nullptr);
}

EmbreeScene::~EmbreeScene() {
    if (scene_) rtcReleaseScene(scene_);
}

void setEmbreeFloatMode() {
    _MM_SET_FLUSH_ZERO_MODE(_MM_FLUSH_ZERO_ON);
    _MM_SET_DENORMALS_ZERO_MODE(_MM_DENORMALS_ZERO_ON);
}

}  // namespace so
