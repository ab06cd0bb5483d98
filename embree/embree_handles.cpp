#include "embree/embree_handles.h"

#include <pmmintrin.h>
#include <xmmintrin.h>

#include <mutex>

#include "core/error.h"

namespace so {

namespace {

const char* codeName(RTCError code) {
    switch (code) {
        case RTC_ERROR_NONE:
            return "RTC_ERROR_NONE";
        case RTC_ERROR_UNKNOWN:
            return "RTC_ERROR_UNKNOWN";
        case RTC_ERROR_INVALID_ARGUMENT:
            return "RTC_ERROR_INVALID_ARGUMENT";
        case RTC_ERROR_INVALID_OPERATION:
            return "RTC_ERROR_INVALID_OPERATION";
        case RTC_ERROR_OUT_OF_MEMORY:
            return "RTC_ERROR_OUT_OF_MEMORY";
        case RTC_ERROR_UNSUPPORTED_CPU:
            return "RTC_ERROR_UNSUPPORTED_CPU";
        case RTC_ERROR_CANCELLED:
            return "RTC_ERROR_CANCELLED";
    }
    return "an unknown code";
}

}  // namespace

// The first error since the last throwIfError, and how many came after it. Fixed-size text: the
// callback may run because memory ran out, so it allocates nothing.
struct EmbreeDevice::ErrorLog {
    std::mutex mutex;  // the callback runs on whichever thread hit the error (TBB's, in builds)
    RTCError code = RTC_ERROR_NONE;
    char text[256] = {};
    unsigned more = 0;
};

namespace {

// Runs inside Embree's C code: it must not throw (noexcept makes any slip a std::terminate, not
// undefined behaviour) and only records; the wrappers throw once Embree has returned.
void onEmbreeError(void* user, RTCError code, const char* str) noexcept {
    auto& log = *static_cast<EmbreeDevice::ErrorLog*>(user);
    const std::lock_guard<std::mutex> lock(log.mutex);
    if (log.code != RTC_ERROR_NONE) {
        ++log.more;
        return;
    }
    log.code = code;
    // One line: control characters (a newline in Embree's text) become spaces.
    size_t n = 0;
    for (; str && str[n] && n + 1 < sizeof log.text; ++n)
        log.text[n] = static_cast<unsigned char>(str[n]) < 0x20 ? ' ' : str[n];
    log.text[n] = '\0';
}

}  // namespace

EmbreeError::EmbreeError(int code, const std::string& text)
    : std::runtime_error("Embree error " + std::to_string(code) + ": " + text), code_(code) {}

EmbreeDevice::EmbreeDevice(const std::string& config) : errors_(std::make_unique<ErrorLog>()) {
    device_ = rtcNewDevice(config.empty() ? nullptr : config.c_str());
    if (!device_) {
        // No device, no callback: Embree keeps the code for the thread.
        const RTCError code = rtcGetDeviceError(nullptr);
        throw EmbreeError(int(code), "cannot create a device with configuration \"" +
                                         printable(config) + "\" (" + codeName(code) + ")");
    }
    // Set right after creation so that no error is missed.
    rtcSetDeviceErrorFunction(device_, onEmbreeError, errors_.get());
    // Masks are compiled into Debian's Embree; the oracle relies on them being honoured. Another
    // build of Embree is the installation's problem, reported like Embree's own errors.
    if (rtcGetDeviceProperty(device_, RTC_DEVICE_PROPERTY_RAY_MASK_SUPPORTED) != 1) {
        rtcReleaseDevice(device_);
        throw EmbreeError(int(RTC_ERROR_UNKNOWN),
                          "this Embree was built without ray masks (EMBREE_RAY_MASK), which the "
                          "oracle needs");
    }
}

EmbreeDevice::~EmbreeDevice() {
    if (!device_) return;
    // A scene still holding the device would otherwise call back into the freed log.
    rtcSetDeviceErrorFunction(device_, nullptr, nullptr);
    rtcReleaseDevice(device_);
}

std::string EmbreeDevice::version() {
    return std::to_string(RTC_VERSION_MAJOR) + "." + std::to_string(RTC_VERSION_MINOR) + "." +
           std::to_string(RTC_VERSION_PATCH);
}

void EmbreeDevice::throwIfError() const {
    RTCError code;
    std::string text;
    {
        const std::lock_guard<std::mutex> lock(errors_->mutex);
        if (errors_->code == RTC_ERROR_NONE) return;
        code = errors_->code;
        text = errors_->text;
        if (text.empty()) text = codeName(code);
        if (errors_->more > 0)
            text += " (and " + std::to_string(errors_->more) + " more Embree errors)";
        errors_->code = RTC_ERROR_NONE;
        errors_->more = 0;
    }
    throw EmbreeError(int(code), text);
}

EmbreeGeometry::EmbreeGeometry(const EmbreeDevice& device, RTCGeometryType type)
    : device_(device), geometry_(rtcNewGeometry(device.get(), type)) {
    try {
        device_.throwIfError();
        if (!geometry_) throw EmbreeError(int(RTC_ERROR_UNKNOWN), "rtcNewGeometry returned null");
    } catch (...) {
        if (geometry_)
            rtcReleaseGeometry(geometry_);  // no destructor runs for a failed constructor
        throw;
    }
}

EmbreeGeometry::~EmbreeGeometry() {
    if (geometry_) rtcReleaseGeometry(geometry_);
}

void* EmbreeGeometry::newBuffer(RTCBufferType type, unsigned slot, RTCFormat format,
                                size_t byteStride, size_t count) {
    void* p = rtcSetNewGeometryBuffer(geometry_, type, slot, format, byteStride, count);
    device_.throwIfError();
    // Embree reports every failure through the callback; a null buffer without one would still
    // be written through.
    if (!p && count > 0)
        throw EmbreeError(int(RTC_ERROR_UNKNOWN), "rtcSetNewGeometryBuffer returned null");
    return p;
}

void EmbreeGeometry::commit() {
    rtcCommitGeometry(geometry_);
    device_.throwIfError();
}

EmbreeScene::EmbreeScene(const EmbreeDevice& device)
    : device_(&device), scene_(rtcNewScene(device.get())) {
    try {
        device.throwIfError();
        if (!scene_) throw EmbreeError(int(RTC_ERROR_UNKNOWN), "rtcNewScene returned null");
    } catch (...) {
        if (scene_) rtcReleaseScene(scene_);  // no destructor runs for a failed constructor
        throw;
    }
}

EmbreeScene::~EmbreeScene() {
    if (scene_) rtcReleaseScene(scene_);
}

void EmbreeScene::attach(const EmbreeGeometry& geometry, unsigned id) {
    rtcAttachGeometryByID(scene_, geometry.get(), id);
    device_->throwIfError();
}

void EmbreeScene::commit() {
    rtcCommitScene(scene_);
    device_->throwIfError();
}

void setEmbreeFloatMode() {
    _MM_SET_FLUSH_ZERO_MODE(_MM_FLUSH_ZERO_ON);
    _MM_SET_DENORMALS_ZERO_MODE(_MM_DENORMALS_ZERO_ON);
}

}  // namespace so
