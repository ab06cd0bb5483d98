// RAII for Embree handles. Every Embree error is fatal: an oracle that silently lost geometry
// would be wrong without saying so.
#pragma once

#include <string>
#include <utility>

#include <embree3/rtcore.h>

namespace so {

class EmbreeDevice {
  public:
    // `config` is Embree's device configuration string (e.g. "threads=2").
    explicit EmbreeDevice(const std::string& config = "");
    ~EmbreeDevice();
    EmbreeDevice(const EmbreeDevice&) = delete;
    EmbreeDevice& operator=(const EmbreeDevice&) = delete;
    RTCDevice get() const { return device_; }
    static std::string version();  // e.g. "3.13.5"

  private:
    RTCDevice device_ = nullptr;
};

class EmbreeScene {
  public:
    explicit EmbreeScene(const EmbreeDevice& device);
    ~EmbreeScene();
    EmbreeScene(const EmbreeScene&) = delete;
    EmbreeScene& operator=(const EmbreeScene&) = delete;
    EmbreeScene(EmbreeScene&& o) noexcept : scene_(std::exchange(o.scene_, nullptr)) {}
    RTCScene get() const { return scene_; }

  private:
    RTCScene scene_ = nullptr;
};

// Embree's documentation asks for flush-to-zero and denormals-are-zero in every thread that
// traces; calling this at the start of each parallel task is cheap.
void setEmbreeFloatMode();

}  // namespace so
