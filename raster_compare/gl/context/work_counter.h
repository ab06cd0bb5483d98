// The counted frame (docs/metrics.md, "Work"): one frame of a technique's counting build
// (gl_program.h, CountingBuild), untimed, in which every pass's work is counted exactly:
// - fragments and texture taps by the shaders themselves, into the work counters (a shader
//   storage buffer at kWorkCounterBinding, read back after each pass);
// - vertices, primitives, shader invocations and clipping by GL_ARB_pipeline_statistics_query;
// - draw calls, and the render targets each pass reads and writes, by watching every draw and
//   clear: libepoxy's entry points for them (its dispatch table of function pointers,
//   epoxy_glDrawArrays, ...) go through counting wrappers, as a tracer (apitrace) interposes on
//   them, which report to the calling thread's WorkCounter, if it has one.
// Several threads may each count a frame in its own context at once (the API's render and compare
// from several threads, docs/api.md).
// A technique needs nothing for its passes to be counted but its PassClock, and SO_TAP before
// each texture lookup in its GLSL (the family frames' lookups have it).
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <string>
#include <tuple>

#include "raster_compare/gl/context/gl_object.h"
#include "raster_compare/gl/context/pass_timer.h"
#include "raster_compare/gl/render/raster_result.h"

namespace so {

// Bytes of one texel of a texture level as an implementation stores it: its components' bits
// (GL's sizes) rounded up to a power of two bytes (24-bit depth in 4 bytes, depth 32F with
// stencil 8 in 8).
uint64_t texelBytes(GLuint texture, GLint level = 0);

// Puts the counting wrappers in libepoxy's slots, once per process; later calls return at once.
// GlContext calls it before its constructor returns, so it runs before any thread of the process
// draws through the raster path: libepoxy's table is one per process, and a slot rewritten while
// another thread fills it lazily (libepoxy resolves an entry point on its first call) could lose
// the wrapper. The wrappers stay: with no WorkCounter on the calling thread they only make the
// call.
void installWorkCounterWrappers();

class WorkCounter final : public PassRecorder {
  public:
    WorkCounter();  // needs the context current; one per thread at a time
    ~WorkCounter() override;
    WorkCounter(const WorkCounter&) = delete;
    WorkCounter& operator=(const WorkCounter&) = delete;

    void begin(const std::string& pass) override;
    void end() override;
    void addRays(uint64_t rays) override;

    // Summed over the frame by pass name ("<light>.<pass>", "camera"); a pass run several times
    // (accumulate's per sample) is the sum of its runs, `passes` how many.
    const std::map<std::string, PassWork>& byPass() const { return byPass_; }

    // What the counting wrappers report (work_counter.cpp); outside a pass, nothing is kept.
    void onDraw();
    // A clear of `buffer` (GL_COLOR, GL_DEPTH, GL_STENCIL, GL_DEPTH_STENCIL) of draw buffer
    // `drawBuffer` of framebuffer `fbo`; glClear's mask is split into those.
    void onClear(GLuint fbo, GLenum buffer, GLint drawBuffer);
    void onClearTexture(GLuint texture, GLint level);

  private:
    // A render target: a texture level, one layer of it or (layer -1) all of them.
    using Image = std::tuple<GLuint, GLint, GLint>;
    void use(const Image& image, bool read, bool written);
    void useAttachment(GLuint fbo, GLenum attachment, bool read, bool written);
    void addTargets(PassWork& w) const;

    GlBuffer counters_;
    std::array<GlQuery, 6> pipeline_;
    std::string pass_;  // the pass being counted; empty between passes
    PassWork current_;
    std::map<Image, std::pair<bool, bool>> targets_;  // read, written in the current pass
    std::map<std::string, PassWork> byPass_;
};

}  // namespace so
