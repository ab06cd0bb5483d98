// The camera pass: what each pixel sees (local position, camera-facing normal, mesh and triangle
// ids), with the same camera as the oracle (core/camera.h), reversed float depth and an infinite
// far plane. Its depth buffer is shared with every light's visibility pass (depth test EQUAL), so
// a technique shades exactly the surfaces the camera pass found.
#pragma once

#include <string>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>

#include "core/camera.h"
#include "core/image.h"
#include "raster_compare/gl/context/gl_object.h"
#include "raster_compare/gl/context/gpu_scene.h"

namespace so {

class CameraPass {
  public:
    // `jitterPixels`: a sub-pixel offset of the projection (a TAA's camera jitter,
    // resolves/resolve.h), in pixels, +y up; every pass drawn with clipFromLocal() moves with it.
    CameraPass(const GpuScene& scene, const CameraDesc& desc, glm::dvec2 jitterPixels = {});

    int width() const { return camera_.width(); }
    int height() const { return camera_.height(); }
    const Camera& camera() const { return camera_; }
    const glm::dmat4& clipFromLocal() const { return clipFromLocal_; }
    // Without the jitter: what the next frame's reprojection projects into.
    const glm::dmat4& unjitteredClipFromLocal() const { return unjitteredClipFromLocal_; }
    const glm::dvec2& jitterPixels() const { return jitterPixels_; }
    const glm::dvec3& lsEye() const { return lsEye_; }
    // The camera pixel's size per unit of distance (2 tan(vfov / 2) / height).
    double pixelScale() const { return pixelScale_; }
    GLuint depthTexture() const { return depth_.get(); }
    // The last render's local position (w: 1 where a surface was hit) and camera-facing normal.
    GLuint positionTexture() const { return position_.get(); }
    GLuint normalTexture() const { return normal_.get(); }
    // POSITION_TEXEL_BYTES and NORMAL_TEXEL_BYTES: for the SO_TAP of a pass that reads them.
    std::string texelBytesDefines() const;

    // Clears and draws; the caller has set the frame's state (depth test and writes on). With
    // `countingBuild`, through a counting build of its program (the counted frame, work_counter.h),
    // made on first use.
    void render(bool countingBuild = false) const;
    // Renders once and returns the local-frame bounds of the surfaces seen (empty if none).
    Bounds3d receiverBounds() const;
    // The nearest and farthest view depth (local units, along the camera's forward axis) of a
    // surface seen, from the same readback as the last receiverBounds(); {0, 0} when nothing was
    // seen or before the first call.
    struct DepthRange {
        double nearest = 0.0, farthest = 0.0;
    };
    const DepthRange& visibleDepthRange() const { return visibleDepths_; }
    // The geometry channels of docs/exr-channels.md from the last render.
    void readGeometry(ChannelImage& image) const;

  private:
    GlProgram buildGeometryProgram() const;

    const GpuScene& scene_;
    Camera camera_;
    glm::dmat4 clipFromLocal_{1.0}, unjitteredClipFromLocal_{1.0};
    glm::dvec2 jitterPixels_{0.0};
    glm::dvec3 lsEye_{0.0};
    double pixelScale_ = 0.0;
    GlProgram program_;
    mutable GlProgram countingProgram_;
    GlTexture position_, normal_, prim_, depth_;
    GlFramebuffer fbo_;
    mutable DepthRange visibleDepths_;
};

// One light's visibility target: V and the predicted aliasing, sharing the camera pass's depth;
// with `depthProbe`, also location 2: what a shadow map's own depth comparison saw (RGBA32F: the
// map's depth at the receiver's texel, the receiver's depth, the map texel's size; cleared to
// -1, -1, 0, 0 where nothing was compared; docs/exr-channels.md), drawn to only while
// setProbing(true): the timed frames write V and the predicted aliasing alone.
class LightTarget {
  public:
    explicit LightTarget(const CameraPass& camera, bool depthProbe = false);
    void bindAndClear() const;
    std::vector<float> readVisibility() const;  // top row first
    GLuint visibilityTexture() const { return visibility_.get(); }
    // VISIBILITY_TEXEL_BYTES: for the SO_TAP of a pass that reads V.
    std::string texelBytesDefines() const;
    std::vector<float> readAliasing() const;
    bool hasDepthProbe() const { return depthProbe_.get() != 0; }
    void setProbing(bool on);                   // location 2 drawn to (with a depth probe)
    std::vector<float> readDepthProbe() const;  // RGBA, top row first; empty without one

  private:
    int width_, height_;
    GlTexture visibility_, aliasing_, depthProbe_;
    GlFramebuffer fbo_;
    bool probing_ = false;
};

}  // namespace so
