// The shadow-map family: per light a map rendered from the light (a depth map, or a moment map
// blurred by a separable Gaussian), then a visibility pass that looks it up. A technique of the
// family derives from ShadowMapTechnique, reads its own parameters into typed members in its
// constructor and configures the family through the hooks below; its GLSL file (techniques/*.glsl)
// defines `float techniqueVisibility(Receiver r)` for the visibility frame
// (shaders/shadow_map.frag) and, for moment maps, `vec4 momentsOf(float t)` for the moment frame
// (shaders/shadow_moments.frag).
//
// Every technique of the family has the common parameters resolution, depth_format and fit, and
// the cascades' cascades, split_lambda, snap and blend (shadowMapParams): any technique's lookup
// runs inside cascades, which are a layout of the family's map, like a cube map's faces. Lengths
// are in texels at the receiver (of the cascade looked up). And every one has screen-space contact
// shadows, contact=on (contact_shadows.h), whose lengths are world units.
#pragma once

#include <array>
#include <memory>
#include <string>

#include <epoxy/gl.h>

#include "core/local_frame.h"

#include "raster_compare/gl/shadow_maps/contact_shadows.h"
#include "raster_compare/gl/shadow_maps/depth_bias.h"
#include "raster_compare/gl/shadow_maps/light_camera.h"
#include "raster_compare/gl/technique.h"

namespace so {

class CameraPass;
class GpuScene;

// What the map holds and how the visibility pass samples it.
enum class MapStorage {
    Depth,                 // depth, point-sampled: the shader compares (and filters) itself
    DepthHardwareCompare,  // depth with GL_COMPARE_REF_TO_TEXTURE and GL_LINEAR
    Moments,               // RGBA32F moments, bilinear, blurred
};

// `fit`: a directional map over the scene's bounds (0) or the receivers in view (1); the adaptive
// map's too.
ParamSpec fitParam();
// The common parameters first, then the technique's own.
ParamTable shadowMapParams(ParamTable own);
// The technique's own parameters, then the depth bias axis (`bias`, defaulting to `defaultBias`,
// and every bias's parameters: depth_bias.h), for a filter that takes any bias.
ParamTable withBiasAxis(ParamTable own, const std::string& defaultBias);

class ShadowMapTechnique : public Technique {
  public:
    static constexpr const char* kFamily = "shadow map";

    explicit ShadowMapTechnique(const ParamValues& values);

    bool filtered() const final { return storage() == MapStorage::Moments; }
    // Cascades fit their slices to the depth range the camera sees, read from the same render.
    bool needsReceiverBounds() const final { return fitToReceivers_ || cascades_.count > 1; }
    // A depth map's visibility pass says what the pixel's own comparison saw
    // (docs/exr-channels.md); moment maps compare no depth.
    bool probesDepth() const final { return storage() == MapStorage::Depth; }
    // One plain map per light; a technique may look up another map instead (smrt:map=adaptive,
    // the virtual shadow map's pages) and call this for the plain one.
    std::unique_ptr<LightTechnique> setUp(const LightSetup& setup) const override;

    int resolution() const { return resolution_; }
    int depthBits() const { return depthBits_; }
    // Directional lights' cascades (count 1: one map); blend: the fraction of each cascade's depth
    // range over which it fades into the next.
    const CascadeSettings& cascades() const { return cascades_; }
    double cascadeBlend() const { return blend_; }
    const ContactShadows& contact() const { return contact_; }
    // The depth bias its table's `bias` chose (withBiasAxis); null for a technique without the
    // axis (smrt and adaptive keep the slope bias; the shadow texture needs none).
    const DepthBias* depthBias() const { return bias_.get(); }

    // The technique's choices.
    virtual MapStorage storage() const { return MapStorage::Depth; }
    // Its GLSL file (shaders.h) and the #defines that configure it (glslDefine keeps precision).
    virtual const char* glsl() const = 0;
    virtual std::string shaderDefines() const { return ""; }
    // GL state for the map pass (polygon offset, culling), undone by endMapPass.
    virtual void beginMapPass() const {}
    virtual void endMapPass() const {}
    // Moment maps: the blur radius in texels (0: none) and the moments of the far plane (t = 1),
    // which the map is cleared to.
    virtual int blurRadius() const { return 0; }
    virtual std::array<float, 4> farMoments() const { return {1, 1, 0, 0}; }
    // Moment maps: bilinear filtering of the map (else point sampling).
    virtual bool bilinearMap() const { return true; }
    // A mesh that is left out of the map and that the visibility GLSL can tell (u_meshId against
    // u_receiverMesh): the shadow texture's receiver; -1 for none. Called once per light.
    virtual int receiverMesh(const GpuScene&) const { return -1; }
    // Uniforms of the visibility program that depend on the light (pcss: its size).
    virtual void setLightUniforms(GLuint /*program*/, const Light& /*light*/,
                                  const LocalFrame& /*frame*/) const {}

  private:
    int resolution_, depthBits_;
    bool fitToReceivers_;
    CascadeSettings cascades_;
    double blend_;
    ContactShadows contact_;
    std::unique_ptr<DepthBias> bias_;
};

// The slope-scaled bias (bias=slope, biases/slope_bias.cpp; and smrt and adaptive, which take no
// other bias): its parameters (slope_factor, min, max, in texels), read from the values, and their
// #defines.
struct SlopeBias {
    static ParamTable params();
    explicit SlopeBias(const ParamValues& values);
    std::string defines() const;
    double factor, minTexels, maxTexels;
};

// The depth buffer's rounding, the one margin the receiver-plane biases keep (bias=receiver-plane,
// adaptive, oriented): `epsilon` steps of the map's last depth bit at the receiver's
// depth. Its #defines turn on shaders/shadow_map.frag's receiver-plane helpers.
struct DepthPrecision {
    static ParamTable params();
    explicit DepthPrecision(const ParamValues& values);
    std::string defines(int depthBits) const;
    double steps;
};

// The uniforms of a visibility frame that come from the camera pass and the light's camera
// (shaders/shadow_map.frag's, which the adaptive map's frame shares): u_clipFromLocal, u_lsEye,
// u_pixelScale, u_lsLight*, u_cosOuter, u_lightClipFromLocal, u_lightViewFromLocal, u_near, u_far,
// u_texelScale.
void setLightCameraUniforms(GLuint program, const CameraPass& camera, const LightCamera& lc);
// The light's part of those: u_lsLightPosition, u_lsLightDirection, u_cosOuter, u_lsEmitNormal,
// u_lightClipFromLocal, u_lightViewFromLocal, u_near, u_far, u_texelScale (the lightmap's bake
// sets the camera's own).
void setLightMapUniforms(GLuint program, const LightCamera& lc);

}  // namespace so
