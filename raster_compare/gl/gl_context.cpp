#include "raster_compare/gl/gl_context.h"

#include <cstdio>
#include <cstdlib>
#include <vector>

#include <epoxy/egl.h>
#include <epoxy/gl.h>

namespace so {

struct GlContext::Egl {
    EGLDisplay display = EGL_NO_DISPLAY;
    EGLContext context = EGL_NO_CONTEXT;
};

namespace {

void GLAPIENTRY onGlDebug(GLenum, GLenum type, GLuint, GLenum severity, GLsizei,
                          const GLchar* message, const void*) {
    if (type == GL_DEBUG_TYPE_ERROR) {
        std::fprintf(stderr, "internal error: GL error: %s\n", message);
#ifndef NDEBUG
        std::abort();  // debug builds: a GL error is a bug, stop where it happens
#endif
    } else if (severity == GL_DEBUG_SEVERITY_HIGH) {
        std::fprintf(stderr, "warning: GL: %s\n", message);
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

}  // namespace

GlContext::GlContext() : egl_(std::make_unique<Egl>()) {
    // Where no EGL driver is found (glvnd without a vendor) eglGetPlatformDisplayEXT has no
    // provider and libepoxy aborts on the first call: ask for its extension first.
    if (!epoxy_has_egl_extension(EGL_NO_DISPLAY, "EGL_EXT_platform_base"))
        throw GlUnavailable(
            "EGL has no EGL_EXT_platform_base: no EGL driver found (is Mesa's libegl-mesa0 "
            "installed?)");
    // A GPU first (the EGL device platform), then Mesa's surfaceless platform.
    if (epoxy_has_egl_extension(EGL_NO_DISPLAY, "EGL_EXT_device_enumeration")) {
        EGLint n = 0;
        EGLDeviceEXT devices[16];
        if (eglQueryDevicesEXT(16, devices, &n)) {
            for (EGLint i = 0; i < n && egl_->context == EGL_NO_CONTEXT; ++i) {
                EGLDisplay d =
                    eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr);
                if (d == EGL_NO_DISPLAY || !eglInitialize(d, nullptr, nullptr)) continue;
                EGLContext c = makeContext(d);
                // Mesa also lists a software device; prefer it only through the surfaceless path.
                if (c != EGL_NO_CONTEXT && eglMakeCurrent(d, EGL_NO_SURFACE, EGL_NO_SURFACE, c)) {
                    const char* r = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
                    if (r && std::string(r).find("llvmpipe") == std::string::npos) {
                        egl_->display = d;
                        egl_->context = c;
                        platform_ = "device";
                        break;
                    }
                    eglMakeCurrent(d, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
                }
                if (c != EGL_NO_CONTEXT) eglDestroyContext(d, c);
                eglTerminate(d);
            }
        }
    }
    if (egl_->context == EGL_NO_CONTEXT) {
        EGLDisplay d =
            eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
        if (d == EGL_NO_DISPLAY)
            throw GlUnavailable(
                "no EGL display could be opened (neither a GPU device nor Mesa surfaceless)");
        if (!eglInitialize(d, nullptr, nullptr))
            throw GlUnavailable("eglInitialize failed on the surfaceless platform");
        EGLContext c = makeContext(d);
        if (c == EGL_NO_CONTEXT) {
            eglTerminate(d);
            throw GlUnavailable("no OpenGL 4.5 core context could be created");
        }
        if (!eglMakeCurrent(d, EGL_NO_SURFACE, EGL_NO_SURFACE, c)) {
            eglDestroyContext(d, c);
            eglTerminate(d);
            throw GlUnavailable("eglMakeCurrent failed");
        }
        egl_->display = d;
        egl_->context = c;
        platform_ = "surfaceless";
    }
    renderer_ = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    version_ = reinterpret_cast<const char*>(glGetString(GL_VERSION));
    if (epoxy_gl_version() < 45)
        throw GlUnavailable("OpenGL 4.5 is needed, the context offers " + version_);
    glEnable(GL_DEBUG_OUTPUT);
    glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
    glDebugMessageCallback(onGlDebug, nullptr);
}

GlContext::~GlContext() {
    if (egl_->display != EGL_NO_DISPLAY) {
        eglMakeCurrent(egl_->display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        if (egl_->context != EGL_NO_CONTEXT) eglDestroyContext(egl_->display, egl_->context);
        eglTerminate(egl_->display);
    }
}

}  // namespace so
