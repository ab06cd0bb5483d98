// RAII for GL object names: one owner, deleted with the matching glDelete* when it goes.
#pragma once

#include <utility>

#include <epoxy/gl.h>

namespace so {

template <void (*Delete)(GLuint)>
class GlName {
  public:
    GlName() = default;
    explicit GlName(GLuint name) : name_(name) {}
    ~GlName() {
        if (name_) Delete(name_);
    }
    GlName(const GlName&) = delete;
    GlName& operator=(const GlName&) = delete;
    GlName(GlName&& o) noexcept : name_(std::exchange(o.name_, 0)) {}
    GlName& operator=(GlName&& o) noexcept {
        if (this != &o) {
            if (name_) Delete(name_);
            name_ = std::exchange(o.name_, 0);
        }
        return *this;
    }
    GLuint get() const { return name_; }

  private:
    GLuint name_ = 0;
};

namespace gl_detail {
inline void deleteBuffer(GLuint n) {
    glDeleteBuffers(1, &n);
}
inline void deleteTexture(GLuint n) {
    glDeleteTextures(1, &n);
}
inline void deleteFramebuffer(GLuint n) {
    glDeleteFramebuffers(1, &n);
}
inline void deleteVertexArray(GLuint n) {
    glDeleteVertexArrays(1, &n);
}
inline void deleteQuery(GLuint n) {
    glDeleteQueries(1, &n);
}
inline void deleteProgram(GLuint n) {
    glDeleteProgram(n);
}
inline void deleteShader(GLuint n) {
    glDeleteShader(n);
}
inline void deleteSampler(GLuint n) {
    glDeleteSamplers(1, &n);
}
}  // namespace gl_detail

using GlBuffer = GlName<gl_detail::deleteBuffer>;
using GlTexture = GlName<gl_detail::deleteTexture>;
using GlFramebuffer = GlName<gl_detail::deleteFramebuffer>;
using GlVertexArray = GlName<gl_detail::deleteVertexArray>;
using GlQuery = GlName<gl_detail::deleteQuery>;
using GlProgram = GlName<gl_detail::deleteProgram>;
using GlShader = GlName<gl_detail::deleteShader>;
using GlSampler = GlName<gl_detail::deleteSampler>;

inline GlBuffer makeBuffer() {
    GLuint n = 0;
    glCreateBuffers(1, &n);
    return GlBuffer(n);
}
inline GlTexture makeTexture(GLenum target) {
    GLuint n = 0;
    glCreateTextures(target, 1, &n);
    return GlTexture(n);
}
// A single-level 2D texture, point-sampled and clamped: the intermediate targets and tables
// that are read texel by texel.
inline GlTexture makeTexture2D(GLenum format, int width, int height) {
    GlTexture t = makeTexture(GL_TEXTURE_2D);
    glTextureStorage2D(t.get(), 1, format, width, height);
    glTextureParameteri(t.get(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(t.get(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTextureParameteri(t.get(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(t.get(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    return t;
}
inline GlFramebuffer makeFramebuffer() {
    GLuint n = 0;
    glCreateFramebuffers(1, &n);
    return GlFramebuffer(n);
}
inline GlVertexArray makeVertexArray() {
    GLuint n = 0;
    glCreateVertexArrays(1, &n);
    return GlVertexArray(n);
}
inline GlQuery makeQuery(GLenum target) {
    GLuint n = 0;
    glCreateQueries(target, 1, &n);
    return GlQuery(n);
}
inline GlSampler makeSampler() {
    GLuint n = 0;
    glCreateSamplers(1, &n);
    return GlSampler(n);
}

}  // namespace so
