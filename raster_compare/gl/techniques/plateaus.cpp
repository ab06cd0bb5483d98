// plateaus: soft planar shadows from plateaus (Haines, "Soft Planar Shadows Using Plateaus", JGT
// 2001). The hard shadow is projected onto the planar receiver from the light's centre (as
// `planar`), and every silhouette edge of the casters, projected the same way, is widened outwards
// into a penumbra: a quad along the edge and a cone at each end, whose attenuation runs from 0 at
// the projected edge to 1 at a rim as wide as the penumbra of a point that high, by similar
// triangles: width = width_scale * light width * h / (D - h), h the point's height above the
// receiver and D the light's. Per pixel the least attenuation wins (Haines drew the cones and
// quads with depth as the attenuation; a MIN blend is the same). Quads are drawn on both sides of
// the edge: inside the hard shadow they lose to its 0, so no orientation is needed. The penumbra
// lies wholly outside the hard shadow (no inner penumbra): the shadow is too large and too dark,
// which penumbra_bias measures. A quad whose ends have different widths is interpolated linearly
// across, as Haines's are. The light's width is pcss's (the side of a square of its area, or
// `light_size`); point, spot and directional lights have none, and plateaus is then `planar`.
// Alpha-tested casters: the projected hard shadow takes their masks (its holes are lit); the
// plateaus are built from the silhouette edges of whole triangles and ignore them, so they darken
// holes within a penumbra's width inside a silhouette edge, and a hole has no penumbra of its own.
// Only the receiver gets a shadow; casters below it or above the light are left out.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include <glm/geometric.hpp>

#include "core/lights/light_kind.h"
#include "raster_compare/gl/context/camera_pass.h"
#include "raster_compare/gl/context/gl_program.h"
#include "raster_compare/gl/context/gpu_scene.h"
#include "raster_compare/gl/context/pass_timer.h"
#include "raster_compare/gl/shaders.h"
#include "raster_compare/gl/shadow_maps/light_camera.h"
#include "raster_compare/gl/technique.h"
#include "raster_compare/gl/volumes/light_facing.h"
#include "raster_compare/gl/volumes/planar_shadow.h"
#include "raster_compare/gl/volumes/receiver_plane.h"
#include "raster_compare/gl/volumes/shadow_volume_geometry.h"

namespace so {
namespace {

struct PlateauSettings {
    int receiver = -1;
    double lightSize = -1.0;  // world units; < 0: the light's own width
    double widthScale = 1.0;
    double lift = 1e-4;
    int coneSegments = 12;
};

// Triangles on the lifted receiver plane, 4 floats per vertex: x, y, z (local frame) and the
// attenuation.
struct PlateauGeometry {
    std::vector<float> vertices;
    size_t edges = 0, cones = 0;
};

// A silhouette vertex projected onto the plane, with its penumbra's width there.
struct PlateauPoint {
    glm::dvec3 lsOnPlane{0.0};
    double width = 0.0;
    bool usable = false;  // above the receiver (within tolerance) and below the light
};

class PlateauBuilder {
  public:
    // P: the lifted plane, normal towards the light; L: the light's homogeneous position (or the
    // direction towards it, w = 0); lsWidth: the light's width scaled by width_scale, local units.
    PlateauBuilder(const WeldedScene& scene, const glm::dvec4& P, const glm::dvec4& L,
                   double lsWidth, double belowTolerance)
        : scene_(scene),
          P_(P),
          L_(L),
          toPlane_(planarProjection(P, L)),
          lsWidth_(lsWidth),
          below_(belowTolerance),
          points_(scene.lsPositions.size()),
          done_(scene.lsPositions.size(), 0) {}

    PlateauGeometry build(int receiverMesh, int segments) {
        // The shadow volumes' light convention: a directional light by the way light travels.
        const glm::dvec4 travel = L_.w != 0.0 ? L_ : glm::dvec4(-glm::dvec3(L_), 0.0);
        std::vector<uint8_t> coned(scene_.lsPositions.size(), 0);
        for (const auto& [a, b] : silhouetteEdges(scene_, travel, receiverMesh))
            if (addEdge(point(a), point(b))) coned[a] = coned[b] = 1;
        for (size_t i = 0; i < coned.size(); ++i)
            if (coned[i]) addCone(point(uint32_t(i)), segments);
        return std::move(g_);
    }

  private:
    const PlateauPoint& point(uint32_t id) {
        PlateauPoint& p = points_[id];
        if (done_[id]) return p;
        done_[id] = 1;
        const glm::dvec4 x(scene_.lsPositions[id], 1.0);
        const double h = glm::dot(P_, x), D = glm::dot(P_, L_);
        if (h < -below_ || (L_.w != 0.0 && h >= D)) return p;
        const glm::dvec4 q = toPlane_ * x;
        p.lsOnPlane = glm::dvec3(q) / q.w;
        // Similar triangles from the light's edges through the point to the plane.
        p.width = L_.w != 0.0 ? lsWidth_ * std::max(h, 0.0) / (D - std::max(h, 0.0)) : 0.0;
        p.usable = std::isfinite(p.width) && std::isfinite(p.lsOnPlane.x) &&
                   std::isfinite(p.lsOnPlane.y) && std::isfinite(p.lsOnPlane.z);
        return p;
    }

    void push(const glm::dvec3& p, double attenuation) {
        g_.vertices.insert(g_.vertices.end(),
                           {float(p.x), float(p.y), float(p.z), float(attenuation)});
    }

    // The quads on both sides of the projected edge a-b; false when nothing was added.
    bool addEdge(const PlateauPoint& a, const PlateauPoint& b) {
        if (!a.usable || !b.usable || (a.width <= 0.0 && b.width <= 0.0)) return false;
        const glm::dvec3 across = glm::cross(glm::dvec3(P_), b.lsOnPlane - a.lsOnPlane);
        const double length = glm::length(across);
        if (!(length > 0.0)) return false;
        for (double side : {-1.0, 1.0}) {
            const glm::dvec3 out = across * (side / length);
            const glm::dvec3 aRim = a.lsOnPlane + a.width * out, bRim = b.lsOnPlane + b.width * out;
            push(a.lsOnPlane, 0.0), push(b.lsOnPlane, 0.0), push(bRim, 1.0);
            push(a.lsOnPlane, 0.0), push(bRim, 1.0), push(aRim, 1.0);
        }
        ++g_.edges;
        return true;
    }

    void addCone(const PlateauPoint& c, int segments) {
        if (!c.usable || c.width <= 0.0) return;
        const glm::dvec3 n(P_);
        const glm::dvec3 u = glm::normalize(
            glm::cross(n, std::fabs(n.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0)));
        const glm::dvec3 v = glm::cross(n, u);
        auto rim = [&](int k) {
            const double a = 2.0 * std::numbers::pi * k / segments;
            return c.lsOnPlane + c.width * (std::cos(a) * u + std::sin(a) * v);
        };
        for (int k = 0; k < segments; ++k)
            push(c.lsOnPlane, 0.0), push(rim(k), 1.0), push(rim(k + 1), 1.0);
        ++g_.cones;
    }

    const WeldedScene& scene_;
    glm::dvec4 P_, L_;
    glm::dmat4 toPlane_;
    double lsWidth_, below_;
    std::vector<PlateauPoint> points_;
    std::vector<uint8_t> done_;
    PlateauGeometry g_;
};

class PlateauLight final : public LightTechnique {
  public:
    PlateauLight(const PlateauSettings& settings, const LightSetup& setup);
    std::vector<std::string> passNames() const override { return {"visibility", "plateaus"}; }
    void renderLightPasses(PassClock&) override {}
    void renderVisibility(PassClock& clock) override;
    RasterLightStats describe() const override;
    uint64_t memoryBytes() const override { return uint64_t(plateauVertices_) * 16u; }

  private:
    void uploadPlateaus(const PlateauGeometry& g);
    void markReceiver() const;

    const GpuScene& scene_;
    ReceiverPlane receiver_;
    glm::dvec4 lsPlane_{0.0};
    size_t edges_ = 0;
    GLsizei plateauVertices_ = 0;
    GlBuffer plateauBuffer_;
    GlVertexArray plateauVao_;
    GlProgram litProg_, markProg_, hardProg_, plateauProg_;
};

PlateauLight::PlateauLight(const PlateauSettings& settings, const LightSetup& setup)
    : scene_(setup.scene) {
    const LocalFrame& frame = scene_.frame();
    const Light& light = setup.light;
    receiver_ = findReceiver(scene_.scene(), frame, settings.receiver, "plateaus");
    const glm::dvec4 L = isDirectional(light) ? glm::dvec4(-glm::normalize(light.wsDirection), 0.0)
                                              : glm::dvec4(frame.lsFromWs(light.wsPosition), 1.0);
    glm::dvec4 P = receiver_.lsPlane;
    if (glm::dot(P, L) < 0.0) P = -P;  // the normal towards the light
    const Bounds3d& b = scene_.lsBounds();
    const double diagonal = glm::length(b.hi - b.lo);
    lsPlane_ = P - glm::dvec4(0, 0, 0, settings.lift * diagonal);
    const double width = settings.lightSize >= 0.0 ? settings.lightSize : lightWidth(light);
    // Points within 1e-3 diagonals below the lifted plane (a box resting on the receiver) count
    // as on it: their penumbra has no width.
    PlateauBuilder builder(scene_.welded(), lsPlane_, L,
                           settings.widthScale * frame.lsLength(width), 1e-3 * diagonal);
    const PlateauGeometry g = builder.build(receiver_.mesh, settings.coneSegments);
    edges_ = g.edges;
    uploadPlateaus(g);
    const CameraPass& camera = setup.camera;
    litProg_ = buildLightFacingProgram(light, scene_, camera);
    markProg_ = buildProgram(scene_.alphaDefines(), shaders::scene_vert,
                             {shaders::alpha_test_glsl, shaders::depth_frag});
    setMat4(markProg_.get(), "u_clipFromLocal", camera.clipFromLocal());
    // The hard shadow takes the casters' alpha masks; the plateaus, built from the silhouette
    // edges of whole triangles, cannot (docs/techniques.md, "Alpha-tested occluders").
    hardProg_ = buildProgram(scene_.alphaDefines(), shaders::planar_glsl,
                             {shaders::alpha_test_glsl, shaders::blend_alpha_frag});
    setMat4(hardProg_.get(), "u_clipFromLocal", camera.clipFromLocal());
    setMat4(hardProg_.get(), "u_projection", flattenOnto(lsPlane_) * planarProjection(lsPlane_, L));
    glProgramUniform4f(hardProg_.get(), glGetUniformLocation(hardProg_.get(), "u_lsPlane"),
                       float(lsPlane_.x), float(lsPlane_.y), float(lsPlane_.z), float(lsPlane_.w));
    setFloat(hardProg_.get(), "u_alpha", 0.0);  // MIN with 0: the hard shadow is black
    plateauProg_ = buildProgram("", shaders::plateaus_glsl, {shaders::plateaus_glsl});
    setMat4(plateauProg_.get(), "u_clipFromLocal", camera.clipFromLocal());
}

void PlateauLight::uploadPlateaus(const PlateauGeometry& g) {
    plateauVertices_ = GLsizei(g.vertices.size() / 4);
    plateauBuffer_ = makeBuffer();
    plateauVao_ = makeVertexArray();
    const GLuint buffer = plateauBuffer_.get(), vao = plateauVao_.get();
    glNamedBufferStorage(buffer, GLsizeiptr(std::max<size_t>(1, g.vertices.size()) * 4),
                         g.vertices.empty() ? nullptr : g.vertices.data(), 0);
    glVertexArrayVertexBuffer(vao, 0, buffer, 0, 16);
    glEnableVertexArrayAttrib(vao, 0);
    glVertexArrayAttribFormat(vao, 0, 4, GL_FLOAT, GL_FALSE, 0);
    glVertexArrayAttribBinding(vao, 0, 0);
}

// The receiver's visible pixels get stencil 1; the shadow is drawn only there (MIN blending
// needs no once-per-pixel rule).
void PlateauLight::markReceiver() const {
    glEnable(GL_STENCIL_TEST);
    glStencilMask(0xff);
    markReceiverStencil(markProg_.get(), scene_, receiver_.mesh, GL_KEEP);
}

void PlateauLight::renderVisibility(PassClock& clock) {
    clock.begin("visibility");
    glUseProgram(litProg_.get());
    scene_.draw(litProg_.get(), false);
    clock.end();
    clock.begin("plateaus");
    markReceiver();
    glColorMaski(1, GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);  // the aliasing target: untouched
    glEnablei(GL_BLEND, 0);
    glBlendEquationi(0, GL_MIN);
    glDepthFunc(GL_GREATER);  // above the receiver, behind anything nearer the camera
    glEnable(GL_CLIP_DISTANCE0);
    glEnable(GL_CLIP_DISTANCE1);
    glUseProgram(hardProg_.get());
    for (size_t m = 0; m < scene_.meshCount(); ++m)
        if (int(m) != receiver_.mesh) scene_.drawMesh(hardProg_.get(), m);
    glDisable(GL_CLIP_DISTANCE0);
    glDisable(GL_CLIP_DISTANCE1);
    glUseProgram(plateauProg_.get());
    glBindVertexArray(plateauVao_.get());
    glDrawArrays(GL_TRIANGLES, 0, plateauVertices_);
    scene_.bind();  // the scene's vertex array, as the frame expects it
    glBlendEquationi(0, GL_FUNC_ADD);
    glDisablei(GL_BLEND, 0);
    glColorMaski(1, GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glDisable(GL_STENCIL_TEST);
    glDepthFunc(GL_EQUAL);
    clock.end();
}

RasterLightStats PlateauLight::describe() const {
    RasterLightStats s;
    s.counts = {{"receiver_mesh", receiver_.mesh},
                {"silhouette_edges", int64_t(edges_)},
                {"plateau_triangles", int64_t(plateauVertices_ / 3)}};
    return s;
}

class Plateaus final : public Technique {
  public:
    static constexpr const char* kFamily = "planar projection";
    static Provenance provenance() {
        return {
            "Haines, \"Soft Planar Shadows Using Plateaus\", Journal of Graphics Tools 6(1), 2001",
            Fidelity::Variant,
            {"the least attenuation wins by a MIN blend where Haines draws cones and quads into "
             "the depth buffer",
             "quads drawn on both sides of every silhouette edge (inside the hard shadow they lose "
             "to its 0)",
             "the light's width is the side of a square of its area (pcss's rule), or light_size"}};
    }
    static ParamTable params() {
        return {receiverParam(),
                {"light_size", -1, -1, 1e6, false,
                 "light width in world units; -1: the scene light's (side of a square of its "
                 "area)"},
                {"width_scale", 1.0, 0.0, 16.0, false,
                 "the plateaus' width over the similar-triangles penumbra width"},
                {"cone_segments", 12, 3, 64, true, "segments of each vertex's cone"},
                {"lift", 1e-4, 0.0, 0.1, false,
                 "the receiver's plane raised towards the light, in scene diagonals"}};
    }
    explicit Plateaus(const ParamValues& v) : Technique(v) {
        settings_.receiver = v.integer("receiver");
        settings_.lightSize = v.real("light_size");
        settings_.widthScale = v.real("width_scale");
        settings_.coneSegments = v.integer("cone_segments");
        settings_.lift = v.real("lift");
    }
    std::unique_ptr<LightTechnique> setUp(const LightSetup& setup) const override {
        return std::make_unique<PlateauLight>(settings_, setup);
    }

  private:
    PlateauSettings settings_;
};

}  // namespace

SO_REGISTER_TECHNIQUE(Plateaus, "plateaus",
                      "soft planar shadows: the projected hard shadow's silhouette widened by "
                      "cones and quads as wide as the penumbra (Haines 2001); the hard shadow "
                      "takes alpha masks, the plateaus (from whole triangles' silhouette edges) "
                      "do not");

}  // namespace so
