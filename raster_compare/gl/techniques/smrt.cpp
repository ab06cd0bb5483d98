// smrt: shadow-map ray tracing, the soft shadows of Unreal 5's virtual shadow maps (SMRT). Unreal's
// shaders are not public: its defaults are its documented cvars (r.Shadow.Virtual.SMRT.*, cited
// beside each parameter in params()), its hit test EEVEE-Next's public one, which traces the same
// way (blender/blender
// source/blender/draw/engines/eevee_next/shaders/eevee_shadow_tracing_lib.glsl,
// shadow_map_trace_hit_check, lines 110-161 at 01a65b6; techniques/smrt_rays.glsl).
// Per pixel `rays` rays leave the receiver toward points on the light (rect: a Fibonacci lattice
// over the rectangle; disk: a Vogel disk on it; sphere and polygon: a disk of the light's width
// facing the receiver; point, spot and directional lights have no size: one direction), the set
// shifted per pixel by interleaved gradient noise (Unreal's per-pixel random light sample points;
// with temporal=on it also moves per frame and a ShadowHistory resolves it). A local light's ray
// is cut where, seen from the light's centre, it spans `max_ray_angle` (MaxRayAngleFromLight); a
// sun's is `ray_length_scale` times the receiver's distance to the camera long
// (RayLengthScaleDirectional). Each is traced from its light end toward the receiver through
// `samples_per_ray` + 1 samples of the depth map, crowding toward the receiver: the first covered
// sample is a plain depth test; after it a sample that lies behind the map's occluder by more than
// the ray's own step is tested against the last occluder in front of the ray, extrapolated along
// its depth slope clamped to `extrapolate_slope` (ExtrapolateMaxSlope*); V is the share of rays
// that hit nothing. Every depth is less the slope bias at the sample.
// map=plain (the default) marches through the family's one map (techniques/smrt.glsl; cascades
// and contact=on as for any of the family). map=adaptive marches through the adaptive technique's
// virtual shadow map (virtual_shadow_map_light.h, its parameters virtual_size, page_size, pool_mb,
// density, refine; passes mark, pages, refine, visibility; shaders/smrt_virtual.frag): each sample
// of a ray is looked up in the finest resident page at or coarser than the level the receiver
// pixel needs, the bias in that page's texels. Pages are asked for by the receivers alone, as
// Unreal does; a sample whose page is not resident reads the finest resident coarser one, and
// the coarsest (one page over the whole map) always is. Directional and spot lights only: point
// and area lights fall back, as adaptive's do, to a cube map of 32-bit depth in the pool's memory,
// here smrt with map=plain (counts cube_fallback = 1, cube_resolution). The march itself is one
// file for both (techniques/smrt_rays.glsl).
#include <cmath>

#include "core/error.h"
#include "raster_compare/gl/context/gl_program.h"
#include "raster_compare/gl/context/gpu_scene.h"
#include "raster_compare/gl/lights/raster_light_kind.h"
#include "raster_compare/gl/provenance.h"
#include "raster_compare/gl/shaders.h"
#include "raster_compare/gl/shadow_maps/light_camera.h"
#include "raster_compare/gl/shadow_maps/shadow_map.h"
#include "raster_compare/gl/shadow_maps/virtual_shadow_map_light.h"
#include "raster_compare/gl/time/temporal_taps.h"

namespace so {
namespace {

// The shadow-map family's parameters that describe the one plain map: map=adaptive has none.
constexpr const char* kPlainMapOnly[] = {"resolution", "depth_format", "cascades", "split_lambda",
                                         "snap",       "blend",        "contact"};
bool plainMapOnly(const std::string& name) {
    for (const char* n : kPlainMapOnly)
        if (name == n) return true;
    return false;
}

class Smrt final : public ShadowMapTechnique {
  public:
    static ParamTable params();
    // Where its design comes from (provenance.h), every deviation from Unreal listed.
    static Provenance provenance() {
        return {
            "Unreal Engine 5 virtual shadow maps, shadow-map ray tracing (the documented "
            "r.Shadow.Virtual.SMRT.* cvars); hit test: Blender EEVEE-Next "
            "eevee_shadow_tracing_lib.glsl (shadow_map_trace_hit_check, 01a65b6)",
            Fidelity::Variant,
            {"Unreal's shader is not public: the hit test is EEVEE-Next's, its 1.05 step threshold "
             "and first-sample plain test included",
             "the slope is in occluder depth per unit of the ray's linear depth, clamped to "
             "Unreal's numbers (5.0, 0.05) whose unit is not published (EEVEE: per ray time, "
             "+-100)",
             "light points: a low-discrepancy set (Fibonacci lattice, Vogel disk) shifted per "
             "pixel by interleaved gradient noise, not Unreal's random sequence",
             "max_ray_angle cuts the ray at the angle seen from the light's centre; Unreal's "
             "exact rule is not published",
             "no TexelDitherScale dither (2.0): the slope bias of SlopeBias instead",
             "no AdaptiveRayCount: every pixel traces all its rays",
             "suns have no angular size here: every ray of a pixel has one direction",
             "map=plain marches one (or a cascaded) depth map; map=adaptive our virtual map: "
             "no page cache, receivers' pages only, our page layout and levels",
             "no screen-space trace before the lookup (r.Shadow.Virtual.ScreenRayLength "
             "0.015) unless contact=on"}};
    }
    explicit Smrt(const ParamValues& v)
        : ShadowMapTechnique(v),
          rays_(v.integer("rays")),
          samples_(v.integer("samples_per_ray")),
          lengthScale_(v.real("ray_length_scale")),
          maxRayAngle_(v.real("max_ray_angle")),
          extrapolateSlope_(v.real("extrapolate_slope")),
          adaptive_(v.integer("map") == 1),
          map_(v, "smrt"),
          bias_(v),
          temporal_(v) {
        // Not ParamSpec::needs, which names a setting other than the default.
        if (adaptive_)
            for (const char* name : kPlainMapOnly)
                if (v.given(name))
                    throwInputError("technique smrt", name, "has no effect with map=adaptive");
    }
    const char* glsl() const override {
        // The march, then its lookups in the plain map.
        static const std::string source = std::string(shaders::smrt_rays_glsl) + shaders::smrt_glsl;
        return source.c_str();
    }
    std::string shaderDefines() const override { return rayDefines() + bias_.defines(); }
    const Resolve* resolve() const override { return temporal_.resolve(); }
    void setLightUniforms(GLuint program, const Light& light,
                          const LocalFrame& frame) const override;
    std::unique_ptr<LightTechnique> setUp(const LightSetup& setup) const override;

  private:
    std::string rayDefines() const {
        return "#define SMRT_RAYS " + std::to_string(rays_) + "\n#define SMRT_SAMPLES " +
               std::to_string(samples_) + "\n" + glslDefine("SMRT_LENGTH_SCALE", lengthScale_) +
               temporal_.defines();
    }
    std::vector<std::string> plainSettings(int cubeResolution) const;
    void setRayLimitUniforms(GLuint program, bool directional) const;

    int rays_, samples_;
    double lengthScale_;
    double maxRayAngle_;       // radians; local lights only
    double extrapolateSlope_;  // negative: the light type's default (kExtrapolateMaxSlope*)
    bool adaptive_;            // map=adaptive
    VirtualMapSettings map_;   // map=adaptive's pages (read, and checked, either way)
    SlopeBias bias_;
    TemporalTaps temporal_;
};

// Unreal's defaults for r.Shadow.Virtual.SMRT.ExtrapolateMaxSlopeDirectional and ...Local
// (documented: indxzero.github.io/ue544cvarwiki, articles r.shadow.virtual.smrt.
// extrapolatemaxslopedirectional and ...local; "Maximum depth slope when extrapolating behind
// occluders"), taken where extrapolate_slope is left negative.
constexpr double kExtrapolateMaxSlopeDirectional = 5.0;
constexpr double kExtrapolateMaxSlopeLocal = 0.05;

ParamTable Smrt::params() {
    // Defaults: Unreal 5's documented cvars (r.Shadow.Virtual.SMRT.*; the UE 5.4 cvar pages at
    // indxzero.github.io/ue544cvarwiki/articles/r.shadow.virtual.smrt.<name>, and their
    // declarations in VirtualShadowMapProjection.cpp): RayCountDirectional and RayCountLocal 7,
    // SamplesPerRayDirectional and SamplesPerRayLocal 8, RayLengthScaleDirectional 1.5,
    // MaxRayAngleFromLight 0.03 (local lights only).
    ParamTable own = {
        {"rays",
         7,
         1,
         64,
         true,
         "rays per pixel toward points on the light (Unreal RayCountDirectional/Local 7)",
         {},
         true},
        {"samples_per_ray", 8, 1, 64, true,
         "depth-map samples along each ray, plus one at the receiver (Unreal SamplesPerRay 8)"},
        {"ray_length_scale", 1.5, 0.0, 1000.0, false,
         "directional lights: ray length in receiver-to-camera distances (Unreal "
         "RayLengthScaleDirectional 1.5)"},
        {"max_ray_angle", 0.03, 0.0, 1.5, false,
         "local lights: the most angle (radians) a ray may span seen from the light's centre, "
         "the rest of it cut (Unreal MaxRayAngleFromLight 0.03; 0: a hard shadow). Suns: no "
         "limit, as in Unreal, whose directional rays ray_length_scale bounds"},
        {"extrapolate_slope", -1, -1, 1000.0, false,
         "the most occluder depth slope (occluder depth per unit of the ray's depth) extrapolated "
         "behind an occluder; 0: flat. Negative: Unreal's default for the light's type "
         "(ExtrapolateMaxSlopeDirectional 5.0 for suns, ExtrapolateMaxSlopeLocal 0.05 for the "
         "rest)"},
        methodParam("map", 0, {"plain", "adaptive"},
                    "the depth map the rays are marched through: plain (resolution, cascades, "
                    "contact) or adaptive, the virtual shadow map's pages (adaptive's parameters; "
                    "point and area lights fall back to map=plain on a cube map of the pool's "
                    "memory)")};
    for (ParamSpec& s : VirtualMapSettings::params("map=adaptive", false))
        own.push_back(std::move(s));
    for (ParamSpec& s : SlopeBias::params()) own.push_back(std::move(s));
    for (ParamSpec& s : TemporalTaps::params()) own.push_back(std::move(s));
    ParamTable p = shadowMapParams(own);
    for (ParamSpec& s : p)
        if (plainMapOnly(s.name)) s.doc = "map=plain: " + s.doc;
    return p;
}

// The ray limits of one light: tan(max_ray_angle) for local lights (-1: none, for suns) and the
// extrapolated slope's bound, a negative extrapolate_slope taking the light type's default.
void Smrt::setRayLimitUniforms(GLuint program, bool directional) const {
    setFloat(program, "u_smrtTanMaxRayAngle", directional ? -1.0 : std::tan(maxRayAngle_));
    const double typeDefault =
        directional ? kExtrapolateMaxSlopeDirectional : kExtrapolateMaxSlopeLocal;
    setFloat(program, "u_smrtMaxSlope", extrapolateSlope_ < 0.0 ? typeDefault : extrapolateSlope_);
}

// map=plain's settings for a point or area light's fallback: every one given except the virtual
// map's, with the cube map's side and 32-bit depth as the pool's.
std::vector<std::string> Smrt::plainSettings(int cubeResolution) const {
    const ParamTable virtualMap = VirtualMapSettings::params();
    std::vector<std::string> settings = {settingText("resolution", cubeResolution),
                                         "depth_format=32"};
    for (const auto& [name, value] : values().all()) {
        bool skip = name == "map" || !values().given(name);
        for (const ParamSpec& s : virtualMap) skip = skip || s.name == name;
        if (!skip) settings.push_back(settingText(name, value));
    }
    return settings;
}

std::unique_ptr<LightTechnique> Smrt::setUp(const LightSetup& setup) const {
    if (!adaptive_) return ShadowMapTechnique::setUp(setup);
    VirtualVisibility visibility;
    visibility.frag = shaders::smrt_virtual_frag;
    visibility.includes = {shaders::taps_glsl, shaders::smrt_rays_glsl};
    visibility.defines = rayDefines();
    visibility.setUniforms = [this](GLuint program, const LightSetup& s) {
        setInt(program, "u_frameIndex", s.frameIndex);  // read only by temporal=on's turn
        setLightUniforms(program, s.light, s.scene.frame());
    };
    const CubeFallback plain = [this](int resolution) {
        return createTechnique("smrt", plainSettings(resolution));
    };
    return setUpVirtualShadowMap(map_, bias_, std::move(visibility), setup, plain, true);
}

// The light's shape as smrt_rays.glsl takes it, world space: u_smrtShape 0 none, 1 the rectangle
// u_lsLightU x u_lsLightV (full edges), 2 the ellipse spanned by them (semi-axes half of each), 3
// a disk of diameter u_smrtWidth facing the receiver (a sphere, a polygon). The light's kind says
// its shape (raster_light_kind.h), so no field a light happens to hold is taken for another shape.
int smrtShape(const RasterLightShape& shape, glm::dvec3& wsU, glm::dvec3& wsV) {
    using Kind = RasterLightShape::Kind;
    switch (shape.kind) {
        case Kind::Point:
        case Kind::Direction:
            return 0;
        case Kind::Rect:
            wsU = shape.wsU, wsV = shape.wsV;
            return 1;
        case Kind::Disk:
            wsU = 2.0 * shape.wsU, wsV = 2.0 * shape.wsV;
            return 2;
        case Kind::Sphere:
        case Kind::Polygon:
            return 3;
    }
    return 0;
}

void Smrt::setLightUniforms(GLuint program, const Light& light, const LocalFrame& frame) const {
    const double toLocal = frame.lsLength(1.0);
    glm::dvec3 u(0.0), v(0.0);
    const RasterLightShape lightShape = rasterLightKind(light.type).shape(light);
    const int shape = smrtShape(lightShape, u, v);
    setInt(program, "u_smrtShape", shape);
    setRayLimitUniforms(program, lightShape.kind == RasterLightShape::Kind::Direction);
    setVec3(program, "u_lsLightU", u * toLocal);
    setVec3(program, "u_lsLightV", v * toLocal);
    setFloat(program, "u_smrtWidth", frame.lsLength(lightWidth(light)));
}

}  // namespace

SO_REGISTER_TECHNIQUE(Smrt, "smrt",
                      "shadow-map ray tracing (Unreal 5's SMRT): rays toward points on the light, "
                      "each marched through the depth map as a height field");

}  // namespace so
