// smrt: shadow-map ray tracing, the soft shadows of Unreal 5's virtual shadow maps, written from
// the published description (Unreal's documentation of r.Shadow.Virtual.SMRT.*; the idea only).
// Per pixel `rays` rays leave the receiver toward points on the light (rect: a low-discrepancy set
// over the rectangle; disk: a Vogel disk on it; sphere and polygon: a disk of the light's width
// facing the receiver; point, spot and directional lights have no size: one ray to the centre or
// along the direction). Each is sampled `samples_per_ray` times through the plain depth map
// rendered from the light's centre, as a height field: the samples crowd toward the receiver
// (t = ((j + h) / n)^2 of the way, h a per-ray fraction), and a sample is blocked where it lies
// behind the depth the map holds by less than the depth its last step covered (the ray crossed
// the height field there; further behind, it passed beside the occluder, which the map from the
// centre cannot tell from a thick one), less the slope bias at the sample. V is the share of rays
// with no blocked sample. Directional rays are `ray_length_scale` times the receiver's distance
// to the camera long (Unreal's RayLengthScaleDirectional, "scaled by distance to the camera");
// rays to a local light run all the way to it. Defaults are Unreal's for directional lights:
// RayCountDirectional 7, SamplesPerRayDirectional 8, RayLengthScaleDirectional 1.5. With
// temporal=on the light points and the samples' fraction turn per frame (interleaved gradient
// noise offset by the frame index, as pcf's taps) and a ShadowHistory resolves them. On the plain
// map only: `map=adaptive` (the virtual shadow map's pages) is not built.
#include <cmath>

#include <glm/geometric.hpp>

#include "core/lights/light_kind.h"
#include "raster_compare/gl/gl_program.h"
#include "raster_compare/gl/light_camera.h"
#include "raster_compare/gl/shaders.h"
#include "raster_compare/gl/shadow_map.h"
#include "raster_compare/gl/temporal_taps.h"

namespace so {
namespace {

class Smrt final : public ShadowMapTechnique {
  public:
    static ParamTable params() {
        ParamTable own = {
            {"rays", 7, 1, 64, true, "rays per pixel toward points on the light", {}, true},
            {"samples_per_ray", 8, 1, 64, true, "depth-map samples along each ray"},
            {"ray_length_scale", 1.5, 0.0, 1000.0, false,
             "directional lights: ray length in receiver-to-camera distances"}};
        for (const ParamSpec& s : SlopeBias::params()) own.push_back(s);
        for (const ParamSpec& s : TemporalTaps::params()) own.push_back(s);
        return shadowMapParams(own);
    }
    explicit Smrt(const ParamValues& v)
        : ShadowMapTechnique(v),
          rays_(v.integer("rays")),
          samples_(v.integer("samples_per_ray")),
          lengthScale_(v.real("ray_length_scale")),
          bias_(v),
          temporal_(v) {}
    const char* glsl() const override { return shaders::smrt_glsl; }
    std::string shaderDefines() const override {
        return "#define SMRT_RAYS " + std::to_string(rays_) + "\n#define SMRT_SAMPLES " +
               std::to_string(samples_) + "\n" + glslDefine("SMRT_LENGTH_SCALE", lengthScale_) +
               bias_.defines() + temporal_.defines();
    }
    std::optional<HistorySettings> history() const override { return temporal_.history(); }
    void setLightUniforms(GLuint program, const Light& light,
                          const LocalFrame& frame) const override;

  private:
    int rays_, samples_;
    double lengthScale_;
    SlopeBias bias_;
    TemporalTaps temporal_;
};

// The light's shape, local units: u_smrtShape 0 none, 1 the rectangle u_lsLightU x u_lsLightV
// (full edges), 2 the disk spanned by them (radius half of each), 3 a disk of diameter
// u_smrtWidth facing the receiver.
void Smrt::setLightUniforms(GLuint program, const Light& light, const LocalFrame& frame) const {
    const double toLocal = frame.lsLength(1.0);
    glm::dvec3 u(0.0), v(0.0);
    int shape = 0;
    // Told apart by what the light holds (no module names a LightType): a rect has its edges, a
    // disk its radius and normal; a sphere or polygon is taken as a disk of its width.
    if (glm::length(light.wsU) > 0.0 && glm::length(light.wsV) > 0.0) {
        shape = 1, u = light.wsU, v = light.wsV;
    } else if (light.radius > 0.0 && glm::length(light.wsNormal) > 0.0 &&
               light.wsVertices.empty()) {
        const glm::dvec3 n = glm::normalize(light.wsNormal);
        const glm::dvec3 h = std::abs(n.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
        u = 2.0 * light.radius * glm::normalize(glm::cross(n, h));
        v = 2.0 * light.radius * glm::cross(n, glm::normalize(u));
        shape = 2;
    } else if (isAreaLight(light)) {
        shape = 3;
    }
    setInt(program, "u_smrtShape", shape);
    setVec3(program, "u_lsLightU", u * toLocal);
    setVec3(program, "u_lsLightV", v * toLocal);
    setFloat(program, "u_smrtWidth", frame.lsLength(lightWidth(light)));
}

}  // namespace

SO_REGISTER_TECHNIQUE(Smrt, "smrt",
                      "shadow-map ray tracing (Unreal 5's SMRT): rays toward points on the light, "
                      "each marched through the depth map as a height field");

}  // namespace so
