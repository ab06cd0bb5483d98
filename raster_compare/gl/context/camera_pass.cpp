#include "raster_compare/gl/context/camera_pass.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>

#include "core/geometry_channels.h"
#include "raster_compare/gl/context/gl_program.h"
#include "raster_compare/gl/context/work_counter.h"
#include "raster_compare/gl/shaders.h"

namespace so {

namespace {

GlTexture makeTarget(GLenum format, int width, int height) {
    GlTexture t = makeTexture(GL_TEXTURE_2D);
    glTextureStorage2D(t.get(), 1, format, width, height);
    return t;
}

// The camera's matrices (the same as generateRay, tested in camera_test) with reversed float
// depth and an infinite far plane for uniform precision; the near plane just inside the scene.
glm::dmat4 cameraClipFromLocal(const GpuScene& scene, const Camera& camera,
                               const glm::dvec3& lsEye) {
    const Bounds3d& lsBounds = scene.lsBounds();
    const double lsNear =
        std::max(0.99 * glm::length(glm::clamp(lsEye, lsBounds.lo, lsBounds.hi) - lsEye), 1e-5);
    glm::dmat4 clipFromView = camera.clipFromView(1.0, 2.0);
    clipFromView[2][2] = 0.0;
    clipFromView[3][2] = scene.frame().wsLength(lsNear);
    clipFromView[2][3] = -1.0;
    return clipFromView * camera.viewFromWorld() * scene.wsFromLs();
}

}  // namespace

CameraPass::CameraPass(const GpuScene& scene, const CameraDesc& desc, glm::dvec2 jitterPixels)
    : scene_(scene), camera_(desc), jitterPixels_(jitterPixels) {
    lsEye_ = scene.frame().lsFromWs(camera_.wsEye());
    unjitteredClipFromLocal_ = cameraClipFromLocal(scene, camera_, lsEye_);
    // clip.xy += (2 jitter / size) clip.w: the image moves by `jitterPixels`.
    glm::dmat4 jitter(1.0);
    jitter[3][0] = 2.0 * jitterPixels.x / double(camera_.width());
    jitter[3][1] = 2.0 * jitterPixels.y / double(camera_.height());
    clipFromLocal_ = jitter * unjitteredClipFromLocal_;
    pixelScale_ =
        2.0 * std::tan(0.5 * desc.vfovDeg * 3.14159265358979323846 / 180.0) / double(height());
    program_ = buildGeometryProgram();
    const int W = width(), H = height();
    position_ = makeTarget(GL_RGBA32F, W, H);
    normal_ = makeTarget(GL_RGBA32F, W, H);
    prim_ = makeTarget(GL_R32F, W, H);
    // Depth and a stencil, which every light's visibility target shares (shadow volumes count
    // in it); 32-bit float depth either way.
    depth_ = makeTarget(GL_DEPTH32F_STENCIL8, W, H);
    fbo_ = makeFramebuffer();
    glNamedFramebufferTexture(fbo_.get(), GL_COLOR_ATTACHMENT0, position_.get(), 0);
    glNamedFramebufferTexture(fbo_.get(), GL_COLOR_ATTACHMENT1, normal_.get(), 0);
    glNamedFramebufferTexture(fbo_.get(), GL_COLOR_ATTACHMENT2, prim_.get(), 0);
    glNamedFramebufferTexture(fbo_.get(), GL_DEPTH_STENCIL_ATTACHMENT, depth_.get(), 0);
    const GLenum buffers[3] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2};
    glNamedFramebufferDrawBuffers(fbo_.get(), 3, buffers);
}

GlProgram CameraPass::buildGeometryProgram() const {
    GlProgram p = buildProgram(scene_.alphaDefines(), shaders::scene_vert,
                               {shaders::alpha_test_glsl, shaders::geometry_frag});
    setMat4(p.get(), "u_clipFromLocal", clipFromLocal_);
    setVec3(p.get(), "u_lsEye", lsEye_);
    return p;
}

void CameraPass::render(bool countingBuild) const {
    if (countingBuild && !countingProgram_.get()) {
        const CountingBuild counting;
        countingProgram_ = buildGeometryProgram();
    }
    const GLuint program = countingBuild ? countingProgram_.get() : program_.get();
    glViewport(0, 0, width(), height());
    glBindFramebuffer(GL_FRAMEBUFFER, fbo_.get());
    const float zero4[4] = {0, 0, 0, 0}, normalClear[4] = {0, 0, 0, -1},
                primClear[4] = {-1, 0, 0, 0}, zero = 0.0f;
    glClearNamedFramebufferfv(fbo_.get(), GL_COLOR, 0, zero4);
    glClearNamedFramebufferfv(fbo_.get(), GL_COLOR, 1, normalClear);
    glClearNamedFramebufferfv(fbo_.get(), GL_COLOR, 2, primClear);
    glClearNamedFramebufferfv(fbo_.get(), GL_DEPTH, 0, &zero);  // reversed depth: 0 is far
    glDepthFunc(GL_GREATER);
    glUseProgram(program);
    scene_.draw(program, true);
}

std::string CameraPass::texelBytesDefines() const {
    return "#define POSITION_TEXEL_BYTES " + std::to_string(texelBytes(position_.get())) +
           "\n#define NORMAL_TEXEL_BYTES " + std::to_string(texelBytes(normal_.get())) + "\n";
}

Bounds3d CameraPass::receiverBounds() const {
    render();
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    const std::vector<float> pos =
        readTextureTopFirst(position_.get(), GL_RGBA, 4, width(), height());
    Bounds3d lsReceivers;
    const glm::dvec3 forward = camera_.wsForward();  // the local frame only scales and shifts
    DepthRange depths{1e300, 0.0};
    for (size_t i = 0; i < size_t(width()) * size_t(height()); ++i) {
        if (pos[4 * i + 3] == 0.0f) continue;
        const glm::dvec3 p(pos[4 * i], pos[4 * i + 1], pos[4 * i + 2]);
        lsReceivers.extend(p);
        const double d = glm::dot(p - lsEye_, forward);
        depths.nearest = std::min(depths.nearest, d);
        depths.farthest = std::max(depths.farthest, d);
    }
    visibleDepths_ = lsReceivers.empty() ? DepthRange{} : depths;
    return lsReceivers;
}

void CameraPass::readGeometry(ChannelImage& image) const {
    const int W = width(), H = height();
    const std::vector<float> pos = readTextureTopFirst(position_.get(), GL_RGBA, 4, W, H),
                             nrm = readTextureTopFirst(normal_.get(), GL_RGBA, 4, W, H),
                             prim = readTextureTopFirst(prim_.get(), GL_RED, 1, W, H);
    GeometryChannelWriter out(image);
    for (size_t i = 0; i < size_t(W) * size_t(H); ++i) {
        if (pos[4 * i + 3] == 0.0f) continue;
        const glm::dvec3 ws =
            scene_.frame().wsFromLs(glm::dvec3(pos[4 * i], pos[4 * i + 1], pos[4 * i + 2]));
        out.set(i, ws, glm::vec3(nrm[4 * i], nrm[4 * i + 1], nrm[4 * i + 2]),
                float(glm::length(ws - camera_.wsEye())), nrm[4 * i + 3], prim[i]);
    }
}

LightTarget::LightTarget(const CameraPass& camera, bool depthProbe)
    : width_(camera.width()), height_(camera.height()) {
    visibility_ = makeTarget(GL_R32F, width_, height_);
    aliasing_ = makeTarget(GL_R32F, width_, height_);
    fbo_ = makeFramebuffer();
    glNamedFramebufferTexture(fbo_.get(), GL_COLOR_ATTACHMENT0, visibility_.get(), 0);
    glNamedFramebufferTexture(fbo_.get(), GL_COLOR_ATTACHMENT1, aliasing_.get(), 0);
    if (depthProbe) {
        depthProbe_ = makeTarget(GL_RGBA32F, width_, height_);
        glNamedFramebufferTexture(fbo_.get(), GL_COLOR_ATTACHMENT2, depthProbe_.get(), 0);
    }
    setProbing(false);
    glNamedFramebufferTexture(fbo_.get(), GL_DEPTH_STENCIL_ATTACHMENT, camera.depthTexture(), 0);
}

void LightTarget::bindAndClear() const {
    glBindFramebuffer(GL_FRAMEBUFFER, fbo_.get());
    const float zero4[4] = {0, 0, 0, 0};
    glClearNamedFramebufferfv(fbo_.get(), GL_COLOR, 0, zero4);
    glClearNamedFramebufferfv(fbo_.get(), GL_COLOR, 1, zero4);
    const float nothingCompared[4] = {-1, -1, 0, 0};
    if (probing_) glClearNamedFramebufferfv(fbo_.get(), GL_COLOR, 2, nothingCompared);
}

void LightTarget::setProbing(bool on) {
    probing_ = on && hasDepthProbe();
    const GLenum buffers[3] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2};
    glNamedFramebufferDrawBuffers(fbo_.get(), probing_ ? 3 : 2, buffers);
}

std::string LightTarget::texelBytesDefines() const {
    return "#define VISIBILITY_TEXEL_BYTES " + std::to_string(texelBytes(visibility_.get())) + "\n";
}

std::vector<float> LightTarget::readVisibility() const {
    return readTextureTopFirst(visibility_.get(), GL_RED, 1, width_, height_);
}

std::vector<float> LightTarget::readAliasing() const {
    return readTextureTopFirst(aliasing_.get(), GL_RED, 1, width_, height_);
}

std::vector<float> LightTarget::readDepthProbe() const {
    if (!hasDepthProbe()) return {};
    return readTextureTopFirst(depthProbe_.get(), GL_RGBA, 4, width_, height_);
}

}  // namespace so
