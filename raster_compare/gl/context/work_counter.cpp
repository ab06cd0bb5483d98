#include "raster_compare/gl/context/work_counter.h"

#include <bit>
#include <type_traits>
#include <vector>

#include <epoxy/egl.h>

#include "core/error.h"
#include "raster_compare/gl/context/gl_program.h"

namespace so {

namespace {

// This thread's counter. Each thread renders in its own context (an EGL context is current in one
// thread), so a draw is reported to the counter of the thread that made it; a thread without one
// (a timed frame, another caller's render) passes straight through.
thread_local WorkCounter* active = nullptr;

// The driver's own entry point (eglGetProcAddress gives core functions too, EGL 1.5): libepoxy's
// slot may still hold its resolver, which would call the slot again, that is the wrapper. It
// dispatches on the calling thread's current context (Mesa's and glvnd's do), so one entry point
// serves every thread's context.
template <typename Fn>
Fn entryPoint(const char* name) {
    auto* f = reinterpret_cast<Fn>(eglGetProcAddress(name));
    SO_CHECK(f != nullptr);
    return f;
}

GLuint drawFramebuffer() {
    GLint fbo = 0;
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &fbo);
    return GLuint(fbo);
}

// Each wrapper reports the call to the active counter, then makes it. Slot is libepoxy's function
// pointer (epoxy_glDrawArrays, ...), Sig its type.
template <auto& Slot, typename Sig>
struct DrawHook;
template <auto& Slot, typename... A>
struct DrawHook<Slot, void (*)(A...)> {
    static inline void (*real)(A...) = nullptr;
    static void call(A... a) {
        if (active) active->onDraw();
        real(a...);
    }
};

// glClearNamedFramebuffer*v(framebuffer, buffer, drawbuffer, value...).
template <auto& Slot, typename Sig>
struct ClearNamedHook;
template <auto& Slot, typename... A>
struct ClearNamedHook<Slot, void (*)(GLuint, GLenum, GLint, A...)> {
    static inline void (*real)(GLuint, GLenum, GLint, A...) = nullptr;
    static void call(GLuint fbo, GLenum buffer, GLint drawBuffer, A... a) {
        if (active) active->onClear(fbo, buffer, drawBuffer);
        real(fbo, buffer, drawBuffer, a...);
    }
};

// glClearBuffer*v(buffer, drawbuffer, value...): the bound draw framebuffer's.
template <auto& Slot, typename Sig>
struct ClearBoundHook;
template <auto& Slot, typename... A>
struct ClearBoundHook<Slot, void (*)(GLenum, GLint, A...)> {
    static inline void (*real)(GLenum, GLint, A...) = nullptr;
    static void call(GLenum buffer, GLint drawBuffer, A... a) {
        if (active) active->onClear(drawFramebuffer(), buffer, drawBuffer);
        real(buffer, drawBuffer, a...);
    }
};

// glClearTex(Sub)Image(texture, level, ...): a partial clear counts its whole level.
template <auto& Slot, typename Sig>
struct ClearTextureHook;
template <auto& Slot, typename... A>
struct ClearTextureHook<Slot, void (*)(GLuint, GLint, A...)> {
    static inline void (*real)(GLuint, GLint, A...) = nullptr;
    static void call(GLuint texture, GLint level, A... a) {
        if (active) active->onClearTexture(texture, level);
        real(texture, level, a...);
    }
};

// glClear(mask): every draw buffer, the depth and the stencil it names.
template <auto& Slot, typename Sig>
struct ClearHook {
    static inline Sig real = nullptr;
    static void call(GLbitfield mask) {
        if (active) {
            const GLuint fbo = drawFramebuffer();
            GLint drawBuffers = 0;
            glGetIntegerv(GL_MAX_DRAW_BUFFERS, &drawBuffers);
            if (mask & GL_COLOR_BUFFER_BIT)
                for (GLint i = 0; i < drawBuffers; ++i) active->onClear(fbo, GL_COLOR, i);
            if (mask & GL_DEPTH_BUFFER_BIT) active->onClear(fbo, GL_DEPTH, 0);
            if (mask & GL_STENCIL_BUFFER_BIT) active->onClear(fbo, GL_STENCIL, 0);
        }
        real(mask);
    }
};

// One entry point's wrapper, installed in libepoxy's slot.
struct Interposed {
    const char* name;
    void (*install)(const char* name);
};

template <template <auto&, typename> class Hook, auto& Slot>
Interposed interpose(const char* name) {
    using H = Hook<Slot, std::remove_reference_t<decltype(Slot)>>;
    return {name, [](const char* n) {
                H::real = entryPoint<decltype(H::real)>(n);
                Slot = &H::call;
            }};
}

#define SO_INTERPOSE(Hook, fn) interpose<Hook, epoxy_##fn>(#fn)

// Every draw and clear entry point of GL 4.5 core.
const std::vector<Interposed>& interposed() {
    static const std::vector<Interposed> all = {
        SO_INTERPOSE(DrawHook, glDrawArrays),
        SO_INTERPOSE(DrawHook, glDrawArraysInstanced),
        SO_INTERPOSE(DrawHook, glDrawArraysInstancedBaseInstance),
        SO_INTERPOSE(DrawHook, glDrawArraysIndirect),
        SO_INTERPOSE(DrawHook, glMultiDrawArrays),
        SO_INTERPOSE(DrawHook, glMultiDrawArraysIndirect),
        SO_INTERPOSE(DrawHook, glDrawElements),
        SO_INTERPOSE(DrawHook, glDrawElementsInstanced),
        SO_INTERPOSE(DrawHook, glDrawElementsBaseVertex),
        SO_INTERPOSE(DrawHook, glDrawElementsInstancedBaseVertex),
        SO_INTERPOSE(DrawHook, glDrawElementsInstancedBaseInstance),
        SO_INTERPOSE(DrawHook, glDrawElementsInstancedBaseVertexBaseInstance),
        SO_INTERPOSE(DrawHook, glDrawRangeElements),
        SO_INTERPOSE(DrawHook, glDrawRangeElementsBaseVertex),
        SO_INTERPOSE(DrawHook, glDrawElementsIndirect),
        SO_INTERPOSE(DrawHook, glMultiDrawElements),
        SO_INTERPOSE(DrawHook, glMultiDrawElementsBaseVertex),
        SO_INTERPOSE(DrawHook, glMultiDrawElementsIndirect),
        SO_INTERPOSE(ClearNamedHook, glClearNamedFramebufferfv),
        SO_INTERPOSE(ClearNamedHook, glClearNamedFramebufferiv),
        SO_INTERPOSE(ClearNamedHook, glClearNamedFramebufferuiv),
        SO_INTERPOSE(ClearNamedHook, glClearNamedFramebufferfi),
        SO_INTERPOSE(ClearBoundHook, glClearBufferfv),
        SO_INTERPOSE(ClearBoundHook, glClearBufferiv),
        SO_INTERPOSE(ClearBoundHook, glClearBufferuiv),
        SO_INTERPOSE(ClearBoundHook, glClearBufferfi),
        SO_INTERPOSE(ClearTextureHook, glClearTexImage),
        SO_INTERPOSE(ClearTextureHook, glClearTexSubImage),
        SO_INTERPOSE(ClearHook, glClear),
    };
    return all;
}

#undef SO_INTERPOSE

constexpr std::array<GLenum, 6> kPipelineQueries = {
    GL_VERTICES_SUBMITTED_ARB,        GL_PRIMITIVES_SUBMITTED_ARB,
    GL_VERTEX_SHADER_INVOCATIONS_ARB, GL_FRAGMENT_SHADER_INVOCATIONS_ARB,
    GL_CLIPPING_INPUT_PRIMITIVES_ARB, GL_CLIPPING_OUTPUT_PRIMITIVES_ARB};

GLint textureLevelParameter(GLuint texture, GLint level, GLenum pname) {
    GLint v = 0;
    glGetTextureLevelParameteriv(texture, level, pname, &v);
    return v;
}

// The texels of a target: one layer, or every layer of a layered attachment.
uint64_t imageTexels(GLuint texture, GLint level, GLint layer) {
    GLint target = 0;
    glGetTextureParameteriv(texture, GL_TEXTURE_TARGET, &target);
    const uint64_t area = uint64_t(textureLevelParameter(texture, level, GL_TEXTURE_WIDTH)) *
                          uint64_t(textureLevelParameter(texture, level, GL_TEXTURE_HEIGHT));
    if (layer >= 0) return area;
    if (target == GL_TEXTURE_CUBE_MAP) return area * 6;
    if (target == GL_TEXTURE_2D_ARRAY || target == GL_TEXTURE_CUBE_MAP_ARRAY ||
        target == GL_TEXTURE_3D)
        return area * uint64_t(textureLevelParameter(texture, level, GL_TEXTURE_DEPTH));
    return area;
}

}  // namespace

uint64_t texelBytes(GLuint texture, GLint level) {
    GLint bits = 0;
    for (GLenum size : {GL_TEXTURE_RED_SIZE, GL_TEXTURE_GREEN_SIZE, GL_TEXTURE_BLUE_SIZE,
                        GL_TEXTURE_ALPHA_SIZE, GL_TEXTURE_DEPTH_SIZE, GL_TEXTURE_STENCIL_SIZE})
        bits += textureLevelParameter(texture, level, size);
    return std::bit_ceil(uint64_t((bits + 7) / 8));
}

void installWorkCounterWrappers() {
    // A function-local static: initialised once, and a second thread waits until it is done.
    static const bool installed = [] {
        for (const Interposed& i : interposed()) i.install(i.name);
        return true;
    }();
    (void)installed;
}

WorkCounter::WorkCounter() {
    SO_CHECK(active == nullptr);  // one per thread: a frame is counted once
    counters_ = makeBuffer();
    glNamedBufferStorage(counters_.get(), 6 * sizeof(GLuint), nullptr, GL_DYNAMIC_STORAGE_BIT);
    // glGenQueries: Mesa 22.3's glCreateQueries refuses these targets (GL_INVALID_ENUM).
    if (epoxy_has_gl_extension("GL_ARB_pipeline_statistics_query"))
        for (GlQuery& q : pipeline_) {
            GLuint name = 0;
            glGenQueries(1, &name);
            q = GlQuery(name);
        }
    active = this;
}

WorkCounter::~WorkCounter() {
    active = nullptr;
}

void WorkCounter::begin(const std::string& pass) {
    SO_CHECK(pass_.empty() && !pass.empty());
    pass_ = pass;
    current_ = {};
    targets_.clear();
    const GLuint zero[6] = {};
    glNamedBufferSubData(counters_.get(), 0, sizeof zero, zero);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kWorkCounterBinding, counters_.get());
    for (size_t i = 0; i < kPipelineQueries.size(); ++i)
        if (pipeline_[i].get()) glBeginQuery(kPipelineQueries[i], pipeline_[i].get());
}

void WorkCounter::addRays(uint64_t rays) {
    SO_CHECK(!pass_.empty());
    current_.counts.raysTraced += rays;
}

void WorkCounter::end() {
    SO_CHECK(!pass_.empty());
    for (size_t i = 0; i < kPipelineQueries.size(); ++i)
        if (pipeline_[i].get()) glEndQuery(kPipelineQueries[i]);
    // The shaders' atomic adds, visible to the read below.
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    GLuint c[6] = {};
    glGetNamedBufferSubData(counters_.get(), 0, sizeof c, c);
    const auto count = [&](int i) { return uint64_t(c[i]) | uint64_t(c[i + 1]) << 32; };
    current_.counts.fragments = count(0);
    current_.counts.textureTaps = count(2);
    current_.tapBytes = count(4);
    if (pipeline_[0].get()) {
        std::array<GLuint64, 6> v{};
        for (size_t i = 0; i < v.size(); ++i)
            glGetQueryObjectui64v(pipeline_[i].get(), GL_QUERY_RESULT, &v[i]);
        current_.pipeline = PipelineCounts{v[0], v[1], v[2], v[3], v[4], v[5]};
    }
    addTargets(current_);
    current_.counts.bytesMoved =
        current_.tapBytes + current_.targetBytesRead + current_.targetBytesWritten;
    current_.counts.passes = 1;
    byPass_[pass_] += current_;
    pass_.clear();
}

void WorkCounter::addTargets(PassWork& w) const {
    for (const auto& [image, use] : targets_) {
        const auto& [texture, level, layer] = image;
        const uint64_t texels = imageTexels(texture, level, layer);
        const uint64_t bytes = texels * texelBytes(texture, level);
        if (use.first) w.targetBytesRead += bytes;
        if (use.second) {
            w.counts.texelsWritten += texels;
            w.targetBytesWritten += bytes;
        }
    }
}

void WorkCounter::use(const Image& image, bool read, bool written) {
    if (!read && !written) return;
    auto& [r, w] = targets_[image];
    r = r || read;
    w = w || written;
}

void WorkCounter::useAttachment(GLuint fbo, GLenum attachment, bool read, bool written) {
    const auto parameter = [&](GLenum pname) {
        GLint v = 0;
        glGetNamedFramebufferAttachmentParameteriv(fbo, attachment, pname, &v);
        return v;
    };
    const GLint type = parameter(GL_FRAMEBUFFER_ATTACHMENT_OBJECT_TYPE);
    if (type == GL_NONE) return;
    SO_CHECK(type == GL_TEXTURE);  // the raster path renders into textures only
    // A cube map's face is its layer (Mesa reports it as the face, with layer 0).
    const GLint face = parameter(GL_FRAMEBUFFER_ATTACHMENT_TEXTURE_CUBE_MAP_FACE);
    const GLint layer = parameter(GL_FRAMEBUFFER_ATTACHMENT_LAYERED) != 0 ? -1
                        : face != 0 ? face - GLint(GL_TEXTURE_CUBE_MAP_POSITIVE_X)
                                    : parameter(GL_FRAMEBUFFER_ATTACHMENT_TEXTURE_LAYER);
    use({GLuint(parameter(GL_FRAMEBUFFER_ATTACHMENT_OBJECT_NAME)),
         parameter(GL_FRAMEBUFFER_ATTACHMENT_TEXTURE_LEVEL), layer},
        read, written);
}

namespace {
bool anyColourWritten(GLint drawBuffer) {
    GLboolean mask[4] = {};
    glGetBooleani_v(GL_COLOR_WRITEMASK, GLuint(drawBuffer), mask);
    return mask[0] || mask[1] || mask[2] || mask[3];
}
// The stencil is written where a face's write mask is on and one of its operations changes it.
bool stencilWritten() {
    for (const auto [mask, sfail, dpfail, dppass] :
         {std::array<GLenum, 4>{GL_STENCIL_WRITEMASK, GL_STENCIL_FAIL, GL_STENCIL_PASS_DEPTH_FAIL,
                                GL_STENCIL_PASS_DEPTH_PASS},
          std::array<GLenum, 4>{GL_STENCIL_BACK_WRITEMASK, GL_STENCIL_BACK_FAIL,
                                GL_STENCIL_BACK_PASS_DEPTH_FAIL,
                                GL_STENCIL_BACK_PASS_DEPTH_PASS}}) {
        GLint m = 0, a = 0, b = 0, c = 0;
        glGetIntegerv(mask, &m);
        glGetIntegerv(sfail, &a);
        glGetIntegerv(dpfail, &b);
        glGetIntegerv(dppass, &c);
        if (m != 0 && (a != GL_KEEP || b != GL_KEEP || c != GL_KEEP)) return true;
    }
    return false;
}
}  // namespace

// The targets a draw reads and writes: each draw buffer's colour (written where its mask lets a
// channel through, read where it blends), the depth (read where its test compares, written where
// also its mask is on) and the stencil (read where its test is on, written where stencilWritten).
void WorkCounter::onDraw() {
    if (pass_.empty()) return;
    ++current_.counts.drawCalls;
    const GLuint fbo = drawFramebuffer();
    if (fbo == 0) return;  // the default framebuffer: none in the raster path (surfaceless)
    GLint drawBuffers = 0;
    glGetIntegerv(GL_MAX_DRAW_BUFFERS, &drawBuffers);
    for (GLint i = 0; i < drawBuffers; ++i) {
        GLint buffer = GL_NONE;
        glGetIntegerv(GL_DRAW_BUFFER0 + GLenum(i), &buffer);
        if (buffer != GL_NONE)
            useAttachment(fbo, GLenum(buffer), glIsEnabledi(GL_BLEND, GLuint(i)),
                          anyColourWritten(i));
    }
    if (glIsEnabled(GL_DEPTH_TEST)) {
        GLint func = GL_LESS;
        GLboolean mask = GL_FALSE;
        glGetIntegerv(GL_DEPTH_FUNC, &func);
        glGetBooleanv(GL_DEPTH_WRITEMASK, &mask);
        useAttachment(fbo, GL_DEPTH_ATTACHMENT, func != GL_ALWAYS && func != GL_NEVER, mask);
    }
    if (glIsEnabled(GL_STENCIL_TEST))
        useAttachment(fbo, GL_STENCIL_ATTACHMENT, true, stencilWritten());
}

// A clear writes its buffer where the write masks let it (colour masks, depth mask, stencil
// write mask), as a draw would.
void WorkCounter::onClear(GLuint fbo, GLenum buffer, GLint drawBuffer) {
    if (pass_.empty() || fbo == 0) return;
    if (buffer == GL_COLOR) {
        const GLuint bound = drawFramebuffer();
        if (bound != fbo) glBindFramebuffer(GL_DRAW_FRAMEBUFFER, fbo);
        GLint attachment = GL_NONE;
        glGetIntegerv(GL_DRAW_BUFFER0 + GLenum(drawBuffer), &attachment);
        if (bound != fbo) glBindFramebuffer(GL_DRAW_FRAMEBUFFER, bound);
        if (attachment != GL_NONE)
            useAttachment(fbo, GLenum(attachment), false, anyColourWritten(drawBuffer));
        return;
    }
    if (buffer == GL_DEPTH || buffer == GL_DEPTH_STENCIL) {
        GLboolean mask = GL_FALSE;
        glGetBooleanv(GL_DEPTH_WRITEMASK, &mask);
        useAttachment(fbo, GL_DEPTH_ATTACHMENT, false, mask);
    }
    if (buffer == GL_STENCIL || buffer == GL_DEPTH_STENCIL) {
        GLint mask = 0;
        glGetIntegerv(GL_STENCIL_WRITEMASK, &mask);
        useAttachment(fbo, GL_STENCIL_ATTACHMENT, false, mask != 0);
    }
}

void WorkCounter::onClearTexture(GLuint texture, GLint level) {
    if (!pass_.empty()) use({texture, level, -1}, false, true);
}

}  // namespace so
