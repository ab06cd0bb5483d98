#include "raster_compare/gl/resolves/resolve_frame.h"

#include <algorithm>

#include "core/scene.h"
#include "raster_compare/gl/context/camera_pass.h"
#include "raster_compare/gl/context/gpu_scene.h"
#include "raster_compare/gl/context/pass_timer.h"
#include "raster_compare/gl/context/work_counter.h"
#include "raster_compare/gl/shaders.h"

namespace so {

namespace {

std::string texelBytesDefine(const char* name, GLuint texture) {
    return "#define " + std::string(name) + " " + std::to_string(texelBytes(texture)) + "\n";
}

}  // namespace

ResolveFrame::ResolveFrame(const ResolveSetup& setup)
    : setup_(setup),
      W_(setup.camera.width()),
      H_(setup.camera.height()),
      history_(makeTexture2D(GL_RGBA32F, W_, H_)),
      resolvedV_(makeTexture2D(GL_R32F, W_, H_)),
      prevHistory_(makeTexture2D(GL_RGBA32F, W_, H_)),
      prevPosition_(makeTexture2D(GL_RGBA32F, W_, H_)),
      fbo_(makeFramebuffer()),
      motion_(makeBuffer()) {
    glNamedFramebufferTexture(fbo_.get(), GL_COLOR_ATTACHMENT0, history_.get(), 0);
    glNamedFramebufferTexture(fbo_.get(), GL_COLOR_ATTACHMENT1, resolvedV_.get(), 0);
    const GLenum buffers[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
    glNamedFramebufferDrawBuffers(fbo_.get(), 2, buffers);
    // One identity per mesh until a frame before sets them (the SSBO must not be empty).
    const size_t meshes = std::max<size_t>(setup.scene.scene().meshes.size(), 1);
    std::vector<float> identity(16 * meshes, 0.0f);
    for (size_t m = 0; m < meshes; ++m)
        for (int k = 0; k < 4; ++k) identity[16 * m + 5 * size_t(k)] = 1.0f;
    glNamedBufferData(motion_.get(), GLsizeiptr(identity.size() * sizeof(float)), identity.data(),
                      GL_DYNAMIC_DRAW);
}

GlProgram ResolveFrame::program(const std::string& defines,
                                const std::vector<const char*>& sources) const {
    std::vector<const char*> fragment = {shaders::resolve_frame_glsl};
    fragment.insert(fragment.end(), sources.begin(), sources.end());
    GlProgram p = buildProgram(defines + setup_.camera.texelBytesDefines() +
                                   setup_.target.texelBytesDefines() +
                                   texelBytesDefine("HISTORY_TEXEL_BYTES", history_.get()),
                               shaders::fullscreen_vert, fragment);
    const GLuint g = p.get();
    setInt(g, "u_visibility", 0);
    setInt(g, "u_position", 1);
    setInt(g, "u_normal", 2);
    setInt(g, "u_prevHistory", 3);
    setInt(g, "u_prevPosition", 4);
    return p;
}

const ResolvedFrame* ResolveFrame::previous() {
    if (!loaded_) {
        before_ =
            setup_.state ? setup_.state->before(setup_.owner, setup_.light.name, W_, H_) : nullptr;
        loaded_ = true;
    }
    return before_;
}

void ResolveFrame::bindInputs(const GlProgram& p) {
    const ResolvedFrame* before = previous();
    const GLuint g = p.get();
    setInt(g, "u_haveHistory", before ? 1 : 0);
    if (before) {
        if (!uploaded_) {
            glTextureSubImage2D(prevHistory_.get(), 0, 0, 0, W_, H_, GL_RGBA, GL_FLOAT,
                                before->history.data());
            glTextureSubImage2D(prevPosition_.get(), 0, 0, 0, W_, H_, GL_RGBA, GL_FLOAT,
                                before->lsPosition.data());
            const std::vector<float> motion =
                previousFromLocalPerMesh(setup_.state, setup_.scene.scene().meshes.size(),
                                         setup_.scene.frame(), before->frame);
            glNamedBufferSubData(motion_.get(), 0, GLsizeiptr(motion.size() * sizeof(float)),
                                 motion.data());
            uploaded_ = true;
        }
        setMat4(g, "u_prevClipFromLocal", before->clipFromLocal);
        setVec3(g, "u_prevLsEye", before->lsEye);
        setVec3(g, "u_prevLsForward", before->lsForward);
        setFloat(g, "u_prevPixelScale", float(before->pixelScale));
    }
    glBindTextureUnit(0, setup_.target.visibilityTexture());
    glBindTextureUnit(1, setup_.camera.positionTexture());
    glBindTextureUnit(2, setup_.camera.normalTexture());
    glBindTextureUnit(3, prevHistory_.get());
    glBindTextureUnit(4, prevPosition_.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, motion_.get());
}

void ResolveFrame::draw(const GlProgram& p) {
    GLint target = 0;
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &target);
    glDisable(GL_DEPTH_TEST);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo_.get());
    glUseProgram(p.get());
    glDrawArrays(GL_TRIANGLES, 0, 3);
    // The resolved V replaces the light's: what raster.exr holds and every metric measures.
    glCopyImageSubData(resolvedV_.get(), GL_TEXTURE_2D, 0, 0, 0, 0,
                       setup_.target.visibilityTexture(), GL_TEXTURE_2D, 0, 0, 0, 0, W_, H_, 1);
    glBindFramebuffer(GL_FRAMEBUFFER, GLuint(target));
    glEnable(GL_DEPTH_TEST);
}

void ResolveFrame::keep(int historyFrames) {
    if (!setup_.state) return;
    ResolvedFrame f;
    f.width = W_;
    f.height = H_;
    const size_t texels = size_t(W_) * size_t(H_);
    const auto bytes = GLsizei(4 * texels * sizeof(float));
    f.history.resize(4 * texels);
    glGetTextureImage(history_.get(), 0, GL_RGBA, GL_FLOAT, bytes, f.history.data());
    f.lsPosition.resize(4 * texels);
    glGetTextureImage(setup_.camera.positionTexture(), 0, GL_RGBA, GL_FLOAT, bytes,
                      f.lsPosition.data());
    std::vector<float> normal(4 * texels);
    glGetTextureImage(setup_.camera.normalTexture(), 0, GL_RGBA, GL_FLOAT, bytes, normal.data());
    for (size_t i = 0; i < texels; ++i)
        f.lsPosition[4 * i + 3] = f.lsPosition[4 * i + 3] != 0.0f ? normal[4 * i + 3] + 1.0f : 0.0f;
    const CameraPass& camera = setup_.camera;
    f.clipFromLocal = camera.unjitteredClipFromLocal();
    f.lsEye = camera.lsEye();
    f.lsForward = camera.camera().wsForward();  // the local frame only scales and shifts
    f.pixelScale = camera.pixelScale();
    f.frame = setup_.scene.frame();
    f.historyFrames = historyFrames;
    setup_.state->keep(setup_.owner, setup_.light.name, std::move(f));
}

OnePassResolve::OnePassResolve(const ResolveSetup& setup, std::string pass,
                               const std::string& defines, const std::vector<const char*>& sources)
    : frame_(setup), pass_(std::move(pass)), program_(frame_.program(defines, sources)) {}

void OnePassResolve::resolve(PassClock& clock) {
    clock.begin(pass_);
    frame_.bindInputs(program_);
    bindOwn();
    frame_.draw(program_);
    unbindOwn();
    clock.end();
    const ResolvedFrame* before = frame_.previous();
    frames_ = before ? before->historyFrames + 1 : 0;
}

uint64_t ResolveFrame::memoryBytes() const {
    // history, the frame before's history and positions RGBA32F; resolved V R32F; the motions.
    return uint64_t(W_) * uint64_t(H_) * (3 * 16 + 4) +
           uint64_t(std::max<size_t>(setup_.scene.scene().meshes.size(), 1)) * 64;
}

}  // namespace so
