#include "raster_compare/gl/volumes/planar_shadow.h"

#include <cmath>
#include <vector>

#include <glm/geometric.hpp>

#include "core/lights/light_kind.h"
#include "raster_compare/gl/context/camera_pass.h"
#include "raster_compare/gl/context/gl_program.h"
#include "raster_compare/gl/context/gpu_scene.h"
#include "raster_compare/gl/context/pass_timer.h"
#include "raster_compare/gl/shaders.h"
#include "raster_compare/gl/volumes/light_facing.h"
#include "raster_compare/gl/volumes/receiver_plane.h"

namespace so {
namespace {

class PlanarLight final : public LightTechnique {
  public:
    PlanarLight(const PlanarSettings& settings, const LightSetup& setup);
    std::vector<std::string> passNames() const override {
        return {"visibility", "projected_shadow"};
    }
    void renderLightPasses(PassClock&) override {}
    void renderVisibility(PassClock& clock) override;
    RasterLightStats describe() const override;
    uint64_t memoryBytes() const override { return 0; }

  private:
    void drawProjected() const;
    void markReceiver() const;

    PlanarSettings settings_;
    std::vector<glm::dmat4> projections_;  // one per plane
    std::vector<glm::dvec4> planes_;       // the planes projected onto (n towards the light)
    const Light& light_;
    const GpuScene& scene_;
    ReceiverPlane receiver_;
    GlProgram litProg_, markProg_, shadowProg_;
};

PlanarLight::PlanarLight(const PlanarSettings& settings, const LightSetup& setup)
    : settings_(settings), light_(setup.light), scene_(setup.scene) {
    const LocalFrame& frame = scene_.frame();
    receiver_ = findReceiver(scene_.scene(), frame, settings.receiver, settings.technique);
    // The light as a homogeneous point: its position, or the point at infinity it shines from.
    const glm::dvec4 L = isDirectional(light_)
                             ? glm::dvec4(-glm::normalize(light_.wsDirection), 0.0)
                             : glm::dvec4(frame.lsFromWs(light_.wsPosition), 1.0);
    glm::dvec4 P = receiver_.lsPlane;
    if (glm::dot(P, L) < 0.0) P = -P;  // the normal towards the light
    const Bounds3d& b = scene_.lsBounds();
    const double diagonal = glm::length(b.hi - b.lo);
    const glm::dvec4 lifted = P - glm::dvec4(0, 0, 0, settings.lift * diagonal);
    // Plane k of `planes`, shifted k spacings towards the light, is projected onto and then
    // flattened back onto the lifted receiver (k = 0: the receiver itself).
    for (int k = 0; k < settings.planes; ++k) {
        const glm::dvec4 shifted = lifted - glm::dvec4(0, 0, 0, k * settings.spacing * diagonal);
        projections_.push_back(flattenOnto(lifted) * planarProjection(shifted, L));
        planes_.push_back(shifted);
    }
    const CameraPass& camera = setup.camera;
    litProg_ = buildLightFacingProgram(light_, scene_, camera);
    markProg_ = buildProgram(scene_.alphaDefines(), shaders::scene_vert,
                             {shaders::alpha_test_glsl, shaders::depth_frag});
    setMat4(markProg_.get(), "u_clipFromLocal", camera.clipFromLocal());
    shadowProg_ = buildProgram(scene_.alphaDefines(), shaders::planar_glsl,
                               {shaders::alpha_test_glsl, shaders::blend_alpha_frag});
    const GLuint sp = shadowProg_.get();
    setMat4(sp, "u_clipFromLocal", camera.clipFromLocal());
    // One projection darkens by alpha (V times 1 - alpha); several are averaged, each taking off
    // alpha / planes once per pixel (the stencil is on).
    setFloat(sp, "u_alpha",
             settings.planes > 1 ? settings.opacity / settings.planes : settings.opacity);
}

void PlanarLight::drawProjected() const {
    for (size_t m = 0; m < scene_.meshCount(); ++m)
        if (int(m) != receiver_.mesh) scene_.drawMesh(shadowProg_.get(), m);
}

// Where the stencil is on, the receiver's visible pixels get 1 and a projection drawn where it
// is 1 sets 0: each projection darkens a pixel once.
void PlanarLight::markReceiver() const {
    markReceiverStencil(markProg_.get(), scene_, receiver_.mesh, GL_ZERO);
}

void PlanarLight::renderVisibility(PassClock& clock) {
    // Lit wherever the light faces the surface (and a spot's cone holds it): no other shadow.
    clock.begin("visibility");
    glUseProgram(litProg_.get());
    scene_.draw(litProg_.get(), false);
    clock.end();
    clock.begin("projected_shadow");
    if (settings_.stencil) {
        glEnable(GL_STENCIL_TEST);
        glStencilMask(0xff);
    }
    glEnable(GL_CLIP_DISTANCE0);
    glEnable(GL_CLIP_DISTANCE1);
    glColorMaski(1, GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);  // the aliasing target: untouched
    for (size_t k = 0; k < projections_.size(); ++k) {
        if (settings_.stencil) markReceiver();
        // Above the receiver (reversed depth: GREATER), behind anything nearer the camera.
        glDepthFunc(GL_GREATER);
        glEnablei(GL_BLEND, 0);
        if (projections_.size() > 1) {
            glBlendEquationi(0, GL_FUNC_REVERSE_SUBTRACT);  // V - alpha / planes
            glBlendFunci(0, GL_ONE, GL_ONE);
        } else {
            glBlendFunci(0, GL_ZERO, GL_ONE_MINUS_SRC_ALPHA);  // V (1 - alpha)
        }
        glUseProgram(shadowProg_.get());
        setMat4(shadowProg_.get(), "u_projection", projections_[k]);
        // Casters below the plane projected onto are clipped (they would cast through it).
        const glm::dvec4& P = planes_[k];
        glProgramUniform4f(shadowProg_.get(), glGetUniformLocation(shadowProg_.get(), "u_lsPlane"),
                           float(P.x), float(P.y), float(P.z), float(P.w));
        drawProjected();
        glBlendEquationi(0, GL_FUNC_ADD);
        glDisablei(GL_BLEND, 0);
    }
    glColorMaski(1, GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glDisable(GL_CLIP_DISTANCE0);
    glDisable(GL_CLIP_DISTANCE1);
    glDisable(GL_STENCIL_TEST);
    glDepthFunc(GL_EQUAL);
    clock.end();
}

RasterLightStats PlanarLight::describe() const {
    RasterLightStats s;
    s.counts = {{"receiver_mesh", receiver_.mesh}, {"planes", int64_t(projections_.size())}};
    return s;
}

}  // namespace

ParamSpec receiverParam() {
    return {
        "receiver", -1,
        -1,         1e6,
        true,       "mesh index (as id.mesh) of the planar receiver; -1: the largest planar mesh"};
}

void markReceiverStencil(GLuint markProgram, const GpuScene& scene, int receiverMesh,
                         GLenum onPass) {
    const GLint zero = 0;
    glClearBufferiv(GL_STENCIL, 0, &zero);
    glStencilFunc(GL_ALWAYS, 1, 0xff);
    glStencilOp(GL_KEEP, GL_KEEP, GL_REPLACE);
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    glDepthFunc(GL_EQUAL);
    glUseProgram(markProgram);
    scene.drawMesh(markProgram, size_t(receiverMesh));
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glStencilFunc(GL_EQUAL, 1, 0xff);
    glStencilOp(GL_KEEP, GL_KEEP, onPass);
}

std::unique_ptr<LightTechnique> setUpPlanarShadow(const PlanarSettings& settings,
                                                  const LightSetup& setup) {
    return std::make_unique<PlanarLight>(settings, setup);
}

}  // namespace so
