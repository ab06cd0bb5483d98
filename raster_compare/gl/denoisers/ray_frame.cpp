#include "raster_compare/gl/denoisers/ray_frame.h"

#include <cmath>

#include "core/scene.h"
#include "raster_compare/gl/context/camera_pass.h"
#include "raster_compare/gl/context/gpu_scene.h"
#include "raster_compare/gl/context/work_counter.h"
#include "raster_compare/gl/shaders.h"
#include "raster_compare/gl/time/temporal_state.h"

namespace so {

std::optional<RayHistoryFrame> RayHistoryStore::before(const std::string& light, int frameIndex,
                                                       int width, int height) const {
    std::lock_guard<std::mutex> lock(mutex_);
    const auto l = frames_.find(light);
    if (l == frames_.end()) return std::nullopt;
    const auto f = l->second.find(frameIndex - 1);
    if (f == l->second.end() || f->second.width != width || f->second.height != height)
        return std::nullopt;
    return f->second;
}

void RayHistoryStore::keep(const std::string& light, int frameIndex, RayHistoryFrame frame) {
    std::lock_guard<std::mutex> lock(mutex_);
    std::map<int, RayHistoryFrame>& byFrame = frames_[light];
    byFrame.erase(byFrame.begin(), byFrame.lower_bound(frameIndex - 1));
    byFrame[frameIndex] = std::move(frame);
}

ScreenTarget::ScreenTarget(GLenum format, int width, int height)
    : texture(makeTexture2D(format, width, height)), fbo(makeFramebuffer()) {
    glNamedFramebufferTexture(fbo.get(), GL_COLOR_ATTACHMENT0, texture.get(), 0);
}

RayFrame::RayFrame(const Light& light, const GpuScene& scene, const CameraPass& camera,
                   int frameIndex, RayHistoryStore& store, RayTarget result,
                   const TemporalState* temporal)
    : light_(light),
      scene_(scene),
      camera_(camera),
      frameIndex_(frameIndex),
      store_(store),
      result_(result),
      temporal_(temporal),
      motion_(makeBuffer()),
      W_(camera.width()),
      H_(camera.height()),
      raw(GL_RG32F, W_, H_),
      accum(GL_RGBA32F, W_, H_),
      prevHistory(GL_RGBA32F, W_, H_),
      prevPosition(GL_RGBA32F, W_, H_),
      filterA(GL_RG32F, W_, H_),
      filterB(GL_RG32F, W_, H_),
      tilesW((W_ + 7) / 8),
      tilesH((H_ + 3) / 4),
      tiles(GL_R32F, tilesW, tilesH) {}

GlProgram RayFrame::program(const char* pass, const std::string& defines,
                            const std::vector<const char*>& sources) const {
    const auto bytes = [](const char* name, GLuint texture) {
        return "#define " + std::string(name) + " " + std::to_string(texelBytes(texture)) + "\n";
    };
    const ScreenTarget& result = result_ == RayTarget::Raw     ? raw
                                 : result_ == RayTarget::Accum ? accum
                                                               : filterA;
    std::vector<const char*> fragment = {shaders::ray_frame_glsl};
    fragment.insert(fragment.end(), sources.begin(), sources.end());
    GlProgram p =
        buildProgram("#define " + std::string(pass) + "\n" + defines + camera_.texelBytesDefines() +
                         bytes("TILE_TEXEL_BYTES", tiles.texture.get()) +
                         bytes("RAW_TEXEL_BYTES", raw.texture.get()) +
                         bytes("ACCUM_TEXEL_BYTES", accum.texture.get()) +
                         bytes("FILTER_TEXEL_BYTES", filterA.texture.get()) +
                         bytes("RESULT_TEXEL_BYTES", result.texture.get()),
                     shaders::fullscreen_vert, fragment);
    const GLuint g = p.get();
    for (const char* input : {"u_raw", "u_accum", "u_filter", "u_result"}) setInt(g, input, 0);
    setInt(g, "u_position", 1);
    setInt(g, "u_normal", 2);
    setInt(g, "u_prevHistory", 3);
    setInt(g, "u_prevPosition", 4);
    setInt(g, "u_tiles", 5);
    setVec3(g, "u_lsEye", camera_.lsEye());
    setFloat(g, "u_pixelScale", camera_.pixelScale());
    return p;
}

void RayFrame::draw(const ScreenTarget& target, const GlProgram& p) const {
    glBindFramebuffer(GL_FRAMEBUFFER, target.fbo.get());
    glUseProgram(p.get());
    glDrawArrays(GL_TRIANGLES, 0, 3);
}

const RayHistoryFrame* RayFrame::previous() {
    if (!loaded_) before_ = store_.before(light_.name, frameIndex_, W_, H_), loaded_ = true;
    return before_ ? &*before_ : nullptr;
}

void RayFrame::bindHistory(const GlProgram& p) {
    const RayHistoryFrame* before = previous();
    const GLuint tp = p.get();
    setInt(tp, "u_haveHistory", before ? 1 : 0);
    if (before) {
        if (!uploaded_) {
            glTextureSubImage2D(prevHistory.texture.get(), 0, 0, 0, W_, H_, GL_RGBA, GL_FLOAT,
                                before->history.data());
            glTextureSubImage2D(prevPosition.texture.get(), 0, 0, 0, W_, H_, GL_RGBA, GL_FLOAT,
                                before->lsPosition.data());
            const std::vector<float> motion = previousFromLocalPerMesh(
                temporal_, scene_.scene().meshes.size(), scene_.frame(), before->frame);
            glNamedBufferData(motion_.get(), GLsizeiptr(motion.size() * sizeof(float)),
                              motion.data(), GL_DYNAMIC_DRAW);
            uploaded_ = true;
        }
        // The frame before's local unit over this frame's (ls = (ws - c) 2^-e).
        const LocalFrame& now = scene_.frame();
        setFloat(tp, "u_prevScale", std::ldexp(1.0, now.exponent - before->frame.exponent));
        setMat4(tp, "u_prevClipFromLocal", before->clipFromLocal);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, motion_.get());
    }
    glBindTextureUnit(0, raw.texture.get());
    glBindTextureUnit(1, camera_.positionTexture());
    glBindTextureUnit(2, camera_.normalTexture());
    glBindTextureUnit(3, prevHistory.texture.get());
    glBindTextureUnit(4, prevPosition.texture.get());
}

void RayFrame::keepHistory(GLuint firstLevel, const std::vector<GLuint>& extra) {
    RayHistoryFrame f;
    f.width = W_;
    f.height = H_;
    const size_t texels = size_t(W_) * size_t(H_);
    f.history.resize(4 * texels);
    glGetTextureImage(accum.texture.get(), 0, GL_RGBA, GL_FLOAT,
                      GLsizei(f.history.size() * sizeof(float)), f.history.data());
    if (firstLevel) {
        std::vector<float> rg(2 * texels);
        glGetTextureImage(firstLevel, 0, GL_RG, GL_FLOAT, GLsizei(rg.size() * sizeof(float)),
                          rg.data());
        for (size_t i = 0; i < texels; ++i) f.history[4 * i] = rg[2 * i];
    }
    for (GLuint texture : extra) {
        std::vector<float> rgba(4 * texels);
        glGetTextureImage(texture, 0, GL_RGBA, GL_FLOAT, GLsizei(rgba.size() * sizeof(float)),
                          rgba.data());
        f.extra.push_back(std::move(rgba));
    }
    f.lsPosition = position;
    f.clipFromLocal = camera_.unjitteredClipFromLocal();
    f.frame = scene_.frame();
    store_.keep(light_.name, frameIndex_, std::move(f));
}

uint64_t RayFrame::memoryBytes() const {
    // raw and two filter targets RG32F; accumulation and the previous frame's history and
    // positions RGBA32F; the tiles R32F.
    return uint64_t(W_) * uint64_t(H_) * (3 * 8 + 3 * 16) + uint64_t(tilesW) * uint64_t(tilesH) * 4;
}

}  // namespace so
