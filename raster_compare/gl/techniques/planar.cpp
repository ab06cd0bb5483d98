// planar: planar projected shadows (Blinn, "Me and My (Fake) Shadow", 1988). Every mesh but the
// receiver is flattened onto the receiver's plane from the light and drawn over it, darkening V to
// 1 - alpha. Only the receiver gets a shadow: shadows on other surfaces and self-shadowing are
// absent by design (false lit, which the metrics count). The course's three fixes are parameters:
// `lift` (the plane raised towards the light against z-fighting, in units of the scene's
// diagonal), `stencil` (the shadow kept to the receiver's pixels and each pixel darkened once:
// without it overlapping projected triangles darken twice, visible with alpha < 1, and the shadow
// runs off the receiver's edges) and `alpha` (the shadow's opacity). Casters below the plane or
// beyond a point light are clipped (w <= 0), not projected into false shadows.
#include <cmath>

#include <glm/geometric.hpp>

#include "raster_compare/gl/camera_pass.h"
#include "raster_compare/gl/gl_program.h"
#include "raster_compare/gl/gpu_scene.h"
#include "raster_compare/gl/light_facing.h"
#include "raster_compare/gl/pass_timer.h"
#include "raster_compare/gl/receiver_plane.h"
#include "raster_compare/gl/shaders.h"
#include "raster_compare/gl/technique.h"

namespace so {
namespace {

class Planar;

class PlanarLight final : public LightTechnique {
  public:
    PlanarLight(const Planar& technique, const LightSetup& setup);
    std::vector<std::string> passNames() const override {
        return {"visibility", "projected_shadow"};
    }
    void renderLightPasses(PassClock&) override {}
    void renderVisibility(PassClock& clock) override;
    RasterLightStats describe() const override;
    uint64_t memoryBytes() const override { return 0; }

  private:
    void drawProjected() const;

    const Planar& technique_;
    const Light& light_;
    const GpuScene& scene_;
    ReceiverPlane receiver_;
    GlProgram litProg_, markProg_, shadowProg_;
};

class Planar final : public Technique {
  public:
    static constexpr const char* kFamily = "planar projection";
    static ParamTable params() {
        return {{"receiver", -1, -1, 1e6, true,
                 "mesh index (as id.mesh) of the planar receiver; -1: the largest planar mesh"},
                {"lift", 1e-4, 0.0, 0.1, false,
                 "the plane raised towards the light, in units of the scene's diagonal"},
                {"stencil", 1, 0, 1, true,
                 "1: shadow only on the receiver's pixels, each darkened once; 0: no stencil"},
                {"alpha", 1.0, 0.0, 1.0, false, "shadow opacity: V = 1 - alpha in shadow"}};
    }
    explicit Planar(const ParamValues& v)
        : Technique(v),
          receiver(v.integer("receiver")),
          lift(v.real("lift")),
          stencil(v.integer("stencil") == 1),
          alpha(v.real("alpha")) {}
    std::unique_ptr<LightTechnique> setUp(const LightSetup& setup) const override {
        return std::make_unique<PlanarLight>(*this, setup);
    }

    int receiver;
    double lift;
    bool stencil;
    double alpha;
};

// Blinn's projection onto the plane P (points x with P . (x, 1) = 0) from the homogeneous light L:
// (P . L) I - L P^T.
glm::dmat4 planarProjection(const glm::dvec4& P, const glm::dvec4& L) {
    glm::dmat4 M(glm::dot(P, L));
    for (int col = 0; col < 4; ++col)
        for (int row = 0; row < 4; ++row) M[col][row] -= L[row] * P[col];
    return M;
}

PlanarLight::PlanarLight(const Planar& technique, const LightSetup& setup)
    : technique_(technique), light_(setup.light), scene_(setup.scene) {
    const LocalFrame& frame = scene_.frame();
    receiver_ = findReceiver(scene_.scene(), frame, technique.receiver, "planar");
    // The light as a homogeneous point: its position, or the point at infinity it shines from.
    const glm::dvec4 L = light_.type == LightType::Directional
                             ? glm::dvec4(-glm::normalize(light_.wsDirection), 0.0)
                             : glm::dvec4(frame.lsFromWs(light_.wsPosition), 1.0);
    glm::dvec4 P = receiver_.lsPlane;
    if (glm::dot(P, L) < 0.0) P = -P;  // the normal towards the light
    const Bounds3d& b = scene_.lsBounds();
    const glm::dvec4 lifted = P - glm::dvec4(0, 0, 0, technique.lift * glm::length(b.hi - b.lo));
    const CameraPass& camera = setup.camera;
    litProg_ = buildLightFacingProgram(light_, scene_, camera);
    markProg_ = buildProgram("", shaders::scene_vert, {shaders::depth_frag});
    setMat4(markProg_.get(), "u_clipFromLocal", camera.clipFromLocal());
    shadowProg_ = buildProgram("", shaders::planar_glsl, {shaders::blend_alpha_frag});
    const GLuint sp = shadowProg_.get();
    setMat4(sp, "u_clipFromLocal", camera.clipFromLocal());
    setMat4(sp, "u_projection", planarProjection(lifted, L));
    glProgramUniform4f(sp, glGetUniformLocation(sp, "u_lsPlane"), float(P.x), float(P.y),
                       float(P.z), float(P.w));
    setFloat(sp, "u_alpha", technique.alpha);
}

void PlanarLight::drawProjected() const {
    for (size_t m = 0; m < scene_.meshCount(); ++m)
        if (int(m) != receiver_.mesh) scene_.drawMesh(m);
}

void PlanarLight::renderVisibility(PassClock& clock) {
    // Lit wherever the light faces the surface (and a spot's cone holds it): no other shadow.
    clock.begin("visibility");
    glUseProgram(litProg_.get());
    scene_.draw(litProg_.get(), false);
    clock.end();
    clock.begin("projected_shadow");
    if (technique_.stencil) {
        // The receiver's visible pixels get 1; the shadow is drawn where it is 1 and sets 0.
        const GLint zero = 0;
        glClearBufferiv(GL_STENCIL, 0, &zero);
        glEnable(GL_STENCIL_TEST);
        glStencilMask(0xff);
        glStencilFunc(GL_ALWAYS, 1, 0xff);
        glStencilOp(GL_KEEP, GL_KEEP, GL_REPLACE);
        glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
        glUseProgram(markProg_.get());
        scene_.drawMesh(size_t(receiver_.mesh));
        glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
        glStencilFunc(GL_EQUAL, 1, 0xff);
        glStencilOp(GL_KEEP, GL_KEEP, GL_ZERO);
    }
    // Above the receiver (reversed depth: GREATER), behind anything nearer the camera.
    glDepthFunc(GL_GREATER);
    glEnable(GL_CLIP_DISTANCE0);
    glEnable(GL_CLIP_DISTANCE1);
    glEnablei(GL_BLEND, 0);
    glBlendFunci(0, GL_ZERO, GL_ONE_MINUS_SRC_ALPHA);
    glColorMaski(1, GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);  // the aliasing target: untouched
    glUseProgram(shadowProg_.get());
    drawProjected();
    glColorMaski(1, GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glDisablei(GL_BLEND, 0);
    glDisable(GL_CLIP_DISTANCE0);
    glDisable(GL_CLIP_DISTANCE1);
    glDisable(GL_STENCIL_TEST);
    glDepthFunc(GL_EQUAL);
    clock.end();
}

RasterLightStats PlanarLight::describe() const {
    RasterLightStats s;
    s.name = light_.name;
    s.type = lightTypeName(light_.type);
    s.family = Planar::kFamily;
    s.counts = {{"receiver_mesh", receiver_.mesh}};
    return s;
}

SO_REGISTER_TECHNIQUE(Planar, "planar",
                      "planar projected shadows: casters flattened onto the receiver's plane");

}  // namespace
}  // namespace so
