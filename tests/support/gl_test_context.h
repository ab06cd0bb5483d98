// The GL tests' context: one for the whole test binary (creating one per test costs more than the
// tests), and REQUIRE_GL(), which skips a test with the reason where no EGL display can be opened.
#pragma once

#include <memory>
#include <string>

#include <gtest/gtest.h>

#include <vector>

#include "raster_compare/gl/context/gl_context.h"
#include "raster_compare/gl/render/renderer.h"
#include "raster_compare/gl/technique.h"

namespace so::test {

inline GlContext* glContext(std::string& why) {
    static std::unique_ptr<GlContext> gl;
    static std::string reason;
    static bool tried = false;
    if (!tried) {
        tried = true;
        try {
            gl = std::make_unique<GlContext>();
        } catch (const GlUnavailable& e) {
            reason = e.what();
        }
    }
    why = reason;
    return gl.get();
}

// One untimed frame of `technique` with `settings` on the shared context (the test must have
// passed REQUIRE_GL), its work counted unless countWork is false.
inline RasterResult renderOneFrame(const Scene& scene, const std::string& technique,
                                   const std::vector<std::string>& settings,
                                   bool countWork = true) {
    std::string why;
    RasterOptions o;
    o.frames = 1;
    o.warmup = 0;
    o.countWork = countWork;
    return renderRaster(scene, *createTechnique(technique, settings), o, *glContext(why));
}

}  // namespace so::test

#define REQUIRE_GL()                                                   \
    std::string whyNoGl;                                               \
    GlContext* gl = glContext(whyNoGl);                                \
    if (!gl) GTEST_SKIP() << "no OpenGL 4.5 through EGL: " << whyNoGl; \
    (void)gl
