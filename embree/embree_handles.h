// RAII for Embree handles, the one Embree library of the product (issue 62): the oracle (oracle/)
// and the raster path's shadow rays (raster_compare/gl/rays/) both make their devices, scenes and
// geometries through these classes, and the scene of a Scene's meshes through triangle_scene.h.
// The single-device rule: Embree's devices are made by EmbreeDevice's constructor
// (embree_handles.cpp) and in no other file of the product, so every device gets the same error
// callback and the same checks (ray masks); a caller chooses only its configuration string. The
// raster path links this library, never the oracle's (docs/architecture.md, rule 3).
//
// Every Embree error is fatal to the result (an oracle that silently lost geometry would be wrong
// without saying so), but not to the caller's process: Embree's error callback runs inside
// Embree's C code, where an exception must not pass, so it only records the error in the device,
// and the wrappers' calls below throw EmbreeError after the Embree call that reported it. Call
// throwIfError() after any Embree call made directly on get().
#pragma once

#include <memory>
#include <stdexcept>
#include <string>
#include <utility>

#include <embree3/rtcore.h>

namespace so {

// An error Embree reported (out of memory, an invalid argument...). what() is one line:
// "Embree error N: text", N Embree's RTCError code.
class EmbreeError : public std::runtime_error {
  public:
    EmbreeError(int code, const std::string& text);
    int code() const { return code_; }

  private:
    int code_;
};

class EmbreeDevice {
  public:
    // `config` is Embree's device configuration string (e.g. "threads=2"). Throws EmbreeError
    // when Embree cannot make the device.
    explicit EmbreeDevice(const std::string& config = "");
    ~EmbreeDevice();
    EmbreeDevice(const EmbreeDevice&) = delete;
    EmbreeDevice& operator=(const EmbreeDevice&) = delete;
    RTCDevice get() const { return device_; }
    static std::string version();  // e.g. "3.13.5"

    // Throws EmbreeError for the first error Embree reported on this device (from any thread)
    // since the last call, and forgets it; later ones are counted in its message.
    void throwIfError() const;

    struct ErrorLog;  // what the callback writes (embree_handles.cpp)

  private:
    // Owned apart from the object: its address is the callback's user pointer.
    std::unique_ptr<ErrorLog> errors_;
    RTCDevice device_ = nullptr;
};

// A geometry being built; released when it goes (the scene it is attached to keeps its own
// reference).
class EmbreeGeometry {
  public:
    EmbreeGeometry(const EmbreeDevice& device, RTCGeometryType type);  // throws EmbreeError
    ~EmbreeGeometry();
    EmbreeGeometry(const EmbreeGeometry&) = delete;
    EmbreeGeometry& operator=(const EmbreeGeometry&) = delete;
    RTCGeometry get() const { return geometry_; }

    // rtcSetNewGeometryBuffer: Embree's buffer of `count` items, never null (out of memory
    // throws EmbreeError).
    void* newBuffer(RTCBufferType type, unsigned slot, RTCFormat format, size_t byteStride,
                    size_t count);
    void commit();  // rtcCommitGeometry; throws EmbreeError

  private:
    const EmbreeDevice& device_;
    RTCGeometry geometry_ = nullptr;
};

// A scene of the device, which must outlive it.
class EmbreeScene {
  public:
    explicit EmbreeScene(const EmbreeDevice& device);  // throws EmbreeError
    ~EmbreeScene();
    EmbreeScene(const EmbreeScene&) = delete;
    EmbreeScene& operator=(const EmbreeScene&) = delete;
    EmbreeScene(EmbreeScene&& o) noexcept
        : device_(o.device_), scene_(std::exchange(o.scene_, nullptr)) {}
    RTCScene get() const { return scene_; }

    void attach(const EmbreeGeometry& geometry, unsigned id);  // throws EmbreeError
    void commit();  // builds the BVH; throws EmbreeError (out of memory, most likely)

  private:
    const EmbreeDevice* device_;
    RTCScene scene_ = nullptr;
};

// Embree's documentation asks for flush-to-zero and denormals-are-zero in every thread that
// traces; calling this at the start of each parallel task is cheap.
void setEmbreeFloatMode();

}  // namespace so
