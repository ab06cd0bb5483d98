#include "raster_compare/gl/volumes/shadow_volume.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include "core/lights/light_kind.h"
#include "raster_compare/gl/context/camera_pass.h"
#include "raster_compare/gl/context/gl_program.h"
#include "raster_compare/gl/context/gpu_scene.h"
#include "raster_compare/gl/context/pass_timer.h"
#include "raster_compare/gl/shaders.h"
#include "raster_compare/gl/volumes/light_facing.h"
#include "raster_compare/gl/volumes/shadow_volume_geometry.h"

namespace so {

namespace {

// The light as the volumes see it: (position, 1), or (direction, 0) for a directional light;
// area lights from their centre, as the shadow maps do.
glm::dvec4 lsLightOf(const Light& light, const LocalFrame& frame) {
    if (isDirectional(light)) return glm::dvec4(glm::normalize(light.wsDirection), 0.0);
    return glm::dvec4(frame.lsFromWs(light.wsPosition), 1.0);
}

// A vertex array over one buffer of floats with `components` per vertex at attribute 0.
struct VertexStream {
    GlBuffer buffer;
    GlVertexArray vao;
    GLsizei vertices = 0;
};

VertexStream makeStream(const std::vector<float>& data, int components) {
    VertexStream s;
    s.buffer = makeBuffer();
    glNamedBufferStorage(s.buffer.get(), GLsizeiptr(std::max<size_t>(1, data.size()) * 4),
                         data.empty() ? nullptr : data.data(), 0);
    s.vao = makeVertexArray();
    glVertexArrayVertexBuffer(s.vao.get(), 0, s.buffer.get(), 0, components * 4);
    glEnableVertexArrayAttrib(s.vao.get(), 0);
    glVertexArrayAttribFormat(s.vao.get(), 0, components, GL_FLOAT, GL_FALSE, 0);
    glVertexArrayAttribBinding(s.vao.get(), 0, 0);
    s.vertices = GLsizei(data.size() / size_t(components));
    return s;
}

// The most fragments `draw` puts on one pixel of a width x height target (additive blending into
// a float target of its own, no depth test); leaves the depth test on and blending off.
template <typename Draw>
int64_t maxCoverage(int width, int height, Draw&& draw) {
    GlTexture counts = makeTexture(GL_TEXTURE_2D);
    glTextureStorage2D(counts.get(), 1, GL_R32F, width, height);
    GlFramebuffer fbo = makeFramebuffer();
    glNamedFramebufferTexture(fbo.get(), GL_COLOR_ATTACHMENT0, counts.get(), 0);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo.get());
    const float zero[4] = {0, 0, 0, 0};
    glClearNamedFramebufferfv(fbo.get(), GL_COLOR, 0, zero);
    glDisable(GL_DEPTH_TEST);
    glEnable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ONE);
    draw();
    glDisable(GL_BLEND);
    glEnable(GL_DEPTH_TEST);
    std::vector<float> v(size_t(width) * size_t(height));
    glGetTextureImage(counts.get(), 0, GL_RED, GL_FLOAT, GLsizei(v.size() * sizeof(float)),
                      v.data());
    float most = 0.0f;
    for (float c : v) most = std::max(most, c);
    return int64_t(most);
}

class ShadowVolumeLight final : public LightTechnique {
  public:
    ShadowVolumeLight(const ShadowVolumeTechnique& technique, const LightSetup& setup);
    std::vector<std::string> passNames() const override { return {"volumes", "visibility"}; }
    void renderLightPasses(PassClock&) override {}
    void renderVisibility(PassClock& clock) override;
    RasterLightStats describe() const override;
    uint64_t memoryBytes() const override;

  private:
    // Reversed depth, so "in front of the surface" is GREATER. A surface lies exactly on its own
    // near cap (the same depths: see capProg_): z-fail must count that cap as behind (strict
    // test), so that it cancels the face where the eye's ray leaves the volume again; z-pass
    // draws no caps and takes the faces through the surface as in front.
    GLenum volumeDepthTest() const { return technique_.zFail() ? GL_GREATER : GL_GEQUAL; }
    void drawVolumes(GLuint program, GLuint capProgram) const;
    void drawNearCaps() const;
    void measureOnce();

    const ShadowVolumeTechnique& technique_;
    const Light& light_;
    const GpuScene& scene_;
    const CameraPass& camera_;
    ShadowVolumeGeometry geometry_;
    int initialCount_ = 0, eyeInside_ = 0;
    VertexStream sides_, farCaps_, nearCaps_;
    GlProgram volumeProg_, capProg_, countProg_, visibilityProg_;
    bool measured_ = false;
    int64_t fillPassed_ = 0, fillTotal_ = 0, maxFaces_ = 0;
};

ShadowVolumeLight::ShadowVolumeLight(const ShadowVolumeTechnique& technique,
                                     const LightSetup& setup)
    : technique_(technique), light_(setup.light), scene_(setup.scene), camera_(setup.camera) {
    const glm::dvec4 lsLight = lsLightOf(light_, scene_.frame());
    geometry_ = buildShadowVolumes(scene_.welded(), lsLight);
    eyeInside_ = volumesContaining(scene_.welded(), lsLight, camera_.lsEye());
    initialCount_ = !technique.zFail() && technique.initialiseCount() ? eyeInside_ : 0;
    sides_ = makeStream(geometry_.sides, 4);
    farCaps_ = makeStream(geometry_.farCaps, 4);
    nearCaps_ = makeStream(geometry_.nearCaps, 3);
    // Volumes and caps are built from whole triangles: an alpha-tested caster is opaque here
    // (docs/techniques.md, "Alpha-tested occluders"), and the caps must match the sides.
    const std::string opaque = "#define ALPHA_TEST_OFF\n";
    volumeProg_ =
        buildProgram(opaque, shaders::volume_vert, {shaders::alpha_test_glsl, shaders::depth_frag});
    setMat4(volumeProg_.get(), "u_clipFromLocal", camera_.clipFromLocal());
    // The near caps through the camera pass's own vertex shader: the same depths to the bit
    // (invariant gl_Position), so a lit surface is never inside its own cap.
    capProg_ =
        buildProgram(opaque, shaders::scene_vert, {shaders::alpha_test_glsl, shaders::depth_frag});
    setMat4(capProg_.get(), "u_clipFromLocal", camera_.clipFromLocal());
    countProg_ = buildProgram("", shaders::volume_vert, {shaders::volume_count_frag});
    setMat4(countProg_.get(), "u_clipFromLocal", camera_.clipFromLocal());
    visibilityProg_ = buildLightFacingProgram(light_, scene_, camera_);
}

// The volume faces z-pass counts (the sides), or z-fail's (sides and both caps): the sides and
// far caps with `program`, the near caps with `capProgram`.
void ShadowVolumeLight::drawVolumes(GLuint program, GLuint capProgram) const {
    glUseProgram(program);
    glBindVertexArray(sides_.vao.get());
    glDrawArrays(GL_TRIANGLES, 0, sides_.vertices);
    if (technique_.zFail()) {
        glBindVertexArray(farCaps_.vao.get());
        glDrawArrays(GL_TRIANGLES, 0, farCaps_.vertices);
        glUseProgram(capProgram);
        drawNearCaps();
    }
}

void ShadowVolumeLight::drawNearCaps() const {
    const GLsizei flipped = GLsizei(3 * geometry_.nearCapsFlipped);
    glBindVertexArray(nearCaps_.vao.get());
    glDrawArrays(GL_TRIANGLES, 0, nearCaps_.vertices - flipped);
    glFrontFace(GL_CW);
    glDrawArrays(GL_TRIANGLES, nearCaps_.vertices - flipped, flipped);
    glFrontFace(GL_CCW);
}

void ShadowVolumeLight::renderVisibility(PassClock& clock) {
    if (!measured_) measureOnce();
    clock.begin("volumes");
    const GLint init = initialCount_ & 0xff;
    glClearBufferiv(GL_STENCIL, 0, &init);
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    glDepthFunc(volumeDepthTest());
    glEnable(GL_STENCIL_TEST);
    glStencilMask(0xff);
    glStencilFunc(GL_ALWAYS, 0, 0xff);
    if (technique_.zFail()) {
        // Carmack: count the faces behind the surface, back faces up, front faces down.
        glStencilOpSeparate(GL_BACK, GL_KEEP, GL_INCR_WRAP, GL_KEEP);
        glStencilOpSeparate(GL_FRONT, GL_KEEP, GL_DECR_WRAP, GL_KEEP);
    } else {
        // Heidmann: count the faces in front of the surface, front faces up, back faces down.
        glStencilOpSeparate(GL_FRONT, GL_KEEP, GL_KEEP, GL_INCR_WRAP);
        glStencilOpSeparate(GL_BACK, GL_KEEP, GL_KEEP, GL_DECR_WRAP);
    }
    drawVolumes(volumeProg_.get(), capProg_.get());
    clock.end();
    clock.begin("visibility");
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glStencilFunc(GL_EQUAL, 0, 0xff);
    glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
    glDepthFunc(GL_EQUAL);
    scene_.bind();
    glUseProgram(visibilityProg_.get());
    scene_.draw(visibilityProg_.get(), false);
    glDisable(GL_STENCIL_TEST);
    clock.end();
}

// The first frame, before the timed passes: the stencil fragments the volumes write (those in
// front of the surface for z-pass, behind it for z-fail) and the most volume faces over one pixel.
void ShadowVolumeLight::measureOnce() {
    measured_ = true;
    GLint target = 0;
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &target);
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    // The stencil passes every fragment: the state and the stencil an earlier light's visibility
    // pass left (GL_EQUAL 0 over its own count) would hide some from the queries.
    glEnable(GL_STENCIL_TEST);
    glStencilFunc(GL_ALWAYS, 0, 0xff);
    glStencilMask(0);
    GlQuery passed = makeQuery(GL_SAMPLES_PASSED), total = makeQuery(GL_SAMPLES_PASSED);
    glDepthFunc(volumeDepthTest());
    glBeginQuery(GL_SAMPLES_PASSED, passed.get());
    drawVolumes(volumeProg_.get(), capProg_.get());
    glEndQuery(GL_SAMPLES_PASSED);
    glDepthFunc(GL_ALWAYS);
    glBeginQuery(GL_SAMPLES_PASSED, total.get());
    drawVolumes(volumeProg_.get(), capProg_.get());
    glEndQuery(GL_SAMPLES_PASSED);
    GLint64 p = 0, t = 0;
    glGetQueryObjecti64v(passed.get(), GL_QUERY_RESULT, &p);
    glGetQueryObjecti64v(total.get(), GL_QUERY_RESULT, &t);
    fillPassed_ = p;
    fillTotal_ = t;
    glStencilMask(0xff);
    glDisable(GL_STENCIL_TEST);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    // The near caps' vec3 positions read as w = 1 in volume.vert.
    maxFaces_ = maxCoverage(camera_.width(), camera_.height(),
                            [&] { drawVolumes(countProg_.get(), countProg_.get()); });
    glBindFramebuffer(GL_FRAMEBUFFER, GLuint(target));
    glDepthFunc(GL_EQUAL);
    scene_.bind();
}

RasterLightStats ShadowVolumeLight::describe() const {
    RasterLightStats s;
    const bool zFail = technique_.zFail();
    s.counts = {
        {"casters", int64_t(geometry_.casters)},
        {"volume_triangles", int64_t(zFail ? geometry_.allTriangles() : geometry_.sideTriangles())},
        {"volume_fill_px", zFail ? fillTotal_ - fillPassed_ : fillPassed_},
        {"volume_fragments", fillTotal_},
        {"max_faces_per_pixel", maxFaces_},
        {"stencil_overflow_possible", maxFaces_ > 255 ? 1 : 0},
        {"eye_in_volumes", eyeInside_},
        {"initial_count", initialCount_}};
    return s;
}

// The volume geometry's buffers (the stencil is the camera pass's).
uint64_t ShadowVolumeLight::memoryBytes() const {
    return uint64_t(geometry_.sides.size() + geometry_.farCaps.size() + geometry_.nearCaps.size()) *
           4;
}

}  // namespace

std::unique_ptr<LightTechnique> ShadowVolumeTechnique::setUp(const LightSetup& setup) const {
    return std::make_unique<ShadowVolumeLight>(*this, setup);
}

}  // namespace so
