// A headless OpenGL 4.5 core context through EGL (docs/techniques.md): the EGL device
// platform when a GPU exposes one, else Mesa's surfaceless platform (llvmpipe). RAII: the context
// is released when the object goes. Contexts made in several threads at once each render on their
// own (the API's render and compare from several threads): they share the process's one EGL
// display, which the first opens and the last to go terminates. A context is current in the
// thread that made it and is used there only.
//
// GL reports errors through KHR_debug's callback, which runs inside the driver, where an exception
// must not pass: the callback records them, and throwIfError() (called by the renderer after each
// technique's frame) throws GlError. Its high-severity warnings are kept for the caller to print
// (takeWarnings): a library does not write to stderr.
#pragma once

#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace so {

// Thrown when no EGL display or GL 4.5 context can be had: callers (tests) skip with its message.
class GlUnavailable : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

// A GL error (a bug in a technique or the renderer, or a driver failure such as out of memory).
// what() is one line: "GL error: message".
class GlError : public std::runtime_error {
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

    // Throws GlError for the first GL error since the last call (from the debug callback, or
    // glGetError where the driver sends no message), and forgets it; later ones are counted in
    // its message, and `where` ("technique pcf") ends it. Needs the context current.
    void throwIfError(const std::string& where = "") const;
    // The driver's high-severity warnings so far, one line each, and forgets them.
    std::vector<std::string> takeWarnings();

    struct Messages;  // what the callback records (gl_context.cpp)

  private:
    struct Egl;
    std::unique_ptr<Egl> egl_;
    // Apart from the object: its address is the callback's user pointer.
    std::unique_ptr<Messages> messages_;
    std::string renderer_, version_, platform_;
};

}  // namespace so
