// A headless OpenGL 4.5 core context through EGL (docs/techniques.md): the EGL device
// platform when a GPU exposes one, else Mesa's surfaceless platform (llvmpipe). RAII: the context
// and display are released when the object goes. KHR_debug errors abort in debug builds.
#pragma once

#include <memory>
#include <stdexcept>
#include <string>

namespace so {

// Thrown when no EGL display or GL 4.5 context can be had: callers (tests) skip with its message.
class GlUnavailable : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

class GlContext {
  public:
    GlContext();  // throws GlUnavailable
    ~GlContext();
    GlContext(const GlContext&) = delete;
    GlContext& operator=(const GlContext&) = delete;

    const std::string& renderer() const { return renderer_; }
    const std::string& version() const { return version_; }
    const std::string& platform() const { return platform_; }  // "device" or "surfaceless"

  private:
    struct Egl;
    std::unique_ptr<Egl> egl_;
    std::string renderer_, version_, platform_;
};

}  // namespace so
