#include "raster_compare/gl/context/gl_context.h"

#include <algorithm>
#include <mutex>
#include <utility>
#include <vector>

#include <epoxy/egl.h>
#include <epoxy/gl.h>

#include "core/error.h"
#include "raster_compare/gl/context/work_counter.h"

namespace so {

// The context and its hold on the process's display (sharedDisplay), released when it goes, also
// when the constructor throws after making it.
struct GlContext::Egl {
    EGLDisplay display = EGL_NO_DISPLAY;
    EGLContext context = EGL_NO_CONTEXT;
    ~Egl();
};

// The callback's record: the first error's text and how many there were since throwIfError, and
// the warnings (at most kMaxWarnings; a driver in trouble can send one per draw).
struct GlContext::Messages {
    static constexpr size_t kMaxWarnings = 100;
    std::mutex mutex;  // GL_DEBUG_OUTPUT_SYNCHRONOUS calls back on the GL thread; cheap insurance
    unsigned errors = 0;
    std::string firstError;
    std::vector<std::string> warnings;
    unsigned droppedWarnings = 0;
};

namespace {

// Runs inside the driver: it must not throw (noexcept turns a slip into std::terminate rather than
// undefined behaviour), so it only records; GlContext::throwIfError throws later.
void GLAPIENTRY onGlDebug(GLenum, GLenum type, GLuint, GLenum severity, GLsizei,
                          const GLchar* message, const void* user) noexcept {
    const bool error = type == GL_DEBUG_TYPE_ERROR;
    if (!error && severity != GL_DEBUG_SEVERITY_HIGH) return;
    auto& m = *static_cast<GlContext::Messages*>(const_cast<void*>(user));
    const std::lock_guard<std::mutex> lock(m.mutex);
    if (error) ++m.errors;  // counted first: it counts even where its text cannot be kept
    try {
        const std::string text = printable(message ? message : "", 300);
        if (error) {
            if (m.errors == 1) m.firstError = text;
        } else if (m.warnings.size() < m.kMaxWarnings) {
            m.warnings.push_back("GL: " + text);
        } else {
            ++m.droppedWarnings;
        }
    } catch (...) {
        // Out of memory for the text: the error is counted, the warning lost.
    }
}

const char* errorName(GLenum e) {
    switch (e) {
        case GL_INVALID_ENUM:
            return "GL_INVALID_ENUM";
        case GL_INVALID_VALUE:
            return "GL_INVALID_VALUE";
        case GL_INVALID_OPERATION:
            return "GL_INVALID_OPERATION";
        case GL_INVALID_FRAMEBUFFER_OPERATION:
            return "GL_INVALID_FRAMEBUFFER_OPERATION";
        case GL_OUT_OF_MEMORY:
            return "GL_OUT_OF_MEMORY";
        case GL_STACK_OVERFLOW:
            return "GL_STACK_OVERFLOW";
        case GL_STACK_UNDERFLOW:
            return "GL_STACK_UNDERFLOW";
        case GL_CONTEXT_LOST:
            return "GL_CONTEXT_LOST";
        default:
            return "an unknown GL error code";
    }
}

EGLContext makeContext(EGLDisplay d) {
    if (!eglBindAPI(EGL_OPENGL_API)) return EGL_NO_CONTEXT;
    const EGLint attrs[] = {EGL_CONTEXT_MAJOR_VERSION,
                            4,
                            EGL_CONTEXT_MINOR_VERSION,
                            5,
                            EGL_CONTEXT_OPENGL_PROFILE_MASK,
                            EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
#ifndef NDEBUG
                            EGL_CONTEXT_OPENGL_DEBUG,
                            EGL_TRUE,
#endif
                            EGL_NONE};
    return eglCreateContext(d, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attrs);
}

// The display every GlContext of the process uses. EGL hands every caller the same display for
// the same platform and device, and eglTerminate ends it for all of them, contexts current in other
// threads included: so the first GlContext opens it, later ones (in any thread) make their own
// context on it, and the last one to go terminates it. `mutex` also orders the first opening.
struct SharedDisplay {
    std::mutex mutex;
    EGLDisplay display = EGL_NO_DISPLAY;
    std::string platform;  // "device" or "surfaceless"
    int users = 0;         // GlContexts holding it
};

SharedDisplay& sharedDisplay() {
    static SharedDisplay d;
    return d;
}

// A GPU's EGL device with a context on it made current, or none: Mesa also lists a software
// device, left to the surfaceless path.
bool openDeviceDisplay(EGLDisplay& display, EGLContext& context) {
    if (!epoxy_has_egl_extension(EGL_NO_DISPLAY, "EGL_EXT_device_enumeration")) return false;
    EGLint n = 0;
    EGLDeviceEXT devices[16];
    if (!eglQueryDevicesEXT(16, devices, &n)) return false;
    for (EGLint i = 0; i < n; ++i) {
        EGLDisplay d = eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr);
        if (d == EGL_NO_DISPLAY || !eglInitialize(d, nullptr, nullptr)) continue;
        EGLContext c = makeContext(d);
        if (c != EGL_NO_CONTEXT && eglMakeCurrent(d, EGL_NO_SURFACE, EGL_NO_SURFACE, c)) {
            const char* r = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
            if (r && std::string(r).find("llvmpipe") == std::string::npos) {
                display = d;
                context = c;
                return true;
            }
            eglMakeCurrent(d, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        }
        if (c != EGL_NO_CONTEXT) eglDestroyContext(d, c);
        eglTerminate(d);
    }
    return false;
}

// Mesa's surfaceless display, initialised; throws GlUnavailable.
EGLDisplay openSurfacelessDisplay() {
    EGLDisplay d =
        eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    if (d == EGL_NO_DISPLAY)
        throw GlUnavailable(
            "no EGL display could be opened (neither a GPU device nor Mesa surfaceless)");
    if (!eglInitialize(d, nullptr, nullptr))
        throw GlUnavailable("eglInitialize failed on the surfaceless platform");
    return d;
}

}  // namespace

GlContext::Egl::~Egl() {
    if (display == EGL_NO_DISPLAY) return;
    if (context != EGL_NO_CONTEXT) {
        eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        eglDestroyContext(display, context);
    }
    SharedDisplay& shared = sharedDisplay();
    const std::lock_guard<std::mutex> lock(shared.mutex);
    if (--shared.users == 0) {
        eglTerminate(shared.display);
        shared.display = EGL_NO_DISPLAY;
    }
}

GlContext::GlContext() : egl_(std::make_unique<Egl>()), messages_(std::make_unique<Messages>()) {
    // Where no EGL driver is found (glvnd without a vendor) eglGetPlatformDisplayEXT has no
    // provider and libepoxy aborts on the first call: ask for its extension first.
    if (!epoxy_has_egl_extension(EGL_NO_DISPLAY, "EGL_EXT_platform_base"))
        throw GlUnavailable(
            "EGL has no EGL_EXT_platform_base: no EGL driver found (is Mesa's libegl-mesa0 "
            "installed?)");
    {
        SharedDisplay& shared = sharedDisplay();
        const std::lock_guard<std::mutex> lock(shared.mutex);
        EGLContext c = EGL_NO_CONTEXT;
        if (shared.users == 0) {
            // A GPU first (the EGL device platform), then Mesa's surfaceless platform.
            EGLDisplay d = EGL_NO_DISPLAY;
            if (openDeviceDisplay(d, c)) {
                shared.platform = "device";
            } else {
                d = openSurfacelessDisplay();
                shared.platform = "surfaceless";
            }
            shared.display = d;
        }
        egl_->display = shared.display;
        ++shared.users;  // from here ~Egl releases it
        platform_ = shared.platform;
        if (c == EGL_NO_CONTEXT) {
            c = makeContext(shared.display);
            if (c == EGL_NO_CONTEXT)
                throw GlUnavailable("no OpenGL 4.5 core context could be created");
        }
        egl_->context = c;
    }
    if (!eglMakeCurrent(egl_->display, EGL_NO_SURFACE, EGL_NO_SURFACE, egl_->context))
        throw GlUnavailable("eglMakeCurrent failed");
    renderer_ = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    version_ = reinterpret_cast<const char*>(glGetString(GL_VERSION));
    if (epoxy_gl_version() < 45)
        throw GlUnavailable("OpenGL 4.5 is needed, the context offers " + version_);
    glEnable(GL_DEBUG_OUTPUT);
    glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
    glDebugMessageCallback(onGlDebug, messages_.get());
    installWorkCounterWrappers();
}

GlContext::~GlContext() = default;  // ~Egl releases the context and the display

void GlContext::throwIfError(const std::string& where) const {
    unsigned errors;
    std::string first;
    {
        const std::lock_guard<std::mutex> lock(messages_->mutex);
        errors = std::exchange(messages_->errors, 0);
        first = std::move(messages_->firstError);
        messages_->firstError.clear();
    }
    // A context without debug output (the driver may send no messages to a non-debug context)
    // still sets GL's error flags. Reading them also clears them; where messages came, they told
    // of the same errors. One flag per kind of error at most, so the loop is short (bounded in
    // case a lost context keeps answering).
    for (int i = 0; i < 16; ++i) {
        const GLenum e = glGetError();
        if (e == GL_NO_ERROR) break;
        if (errors == 0) first = std::string("glGetError: ") + errorName(e);
        errors = std::max(errors, 1u);
    }
    if (errors == 0) return;
    if (first.empty()) first = "(the driver's message was lost)";
    if (errors > 1) first += " (and " + std::to_string(errors - 1) + " more GL errors)";
    if (!where.empty()) first += " [" + where + "]";
    throw GlError("GL error: " + first);
}

std::vector<std::string> GlContext::takeWarnings() {
    const std::lock_guard<std::mutex> lock(messages_->mutex);
    std::vector<std::string> out = std::move(messages_->warnings);
    messages_->warnings.clear();
    if (messages_->droppedWarnings > 0)
        out.push_back("GL: " + std::to_string(std::exchange(messages_->droppedWarnings, 0)) +
                      " more warnings not kept");
    return out;
}

}  // namespace so
