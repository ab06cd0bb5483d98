// The shadow-map camera of each light (docs/techniques.md, "Light cameras"), in the local frame:
//   directional: orthographic in a light frame, fitted to the scene's bounds;
//   spot: perspective covering the outer cone (at most 170 degrees);
//   point, and area lights (from their centre): a cube map of six 90-degree faces;
//   directional with cascades: one orthographic map per slice of the view's depth range
//   (fitCascades), the layers of a 2D array texture.
// Depth runs 0 (near) to 1 (far) (glClipControl GL_ZERO_TO_ONE); near and far enclose the bounds.
#pragma once

#include <array>
#include <string>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "core/local_frame.h"
#include "core/scene.h"

namespace so {

struct LightCamera {
    enum class Kind { Ortho, Perspective, Cube, Cascades };
    static constexpr int kMaxFaces = 8;
    Kind kind = Kind::Ortho;
    int faces = 1;  // 6 for a cube, the cascade count for cascades
    std::array<glm::dmat4, kMaxFaces> viewFromLocal{};
    std::array<glm::dmat4, kMaxFaces> clipFromView{};  // per face (cube faces share one)
    double near = 0.0, far = 1.0;  // cascades share them: depth always spans the whole scene
    // Ortho: the local-space size of one texel (cascades: the first's); perspective and cube: per
    // unit of depth along the view axis (2 tan(fov / 2) / resolution).
    double texelScale = 0.0;
    // Cascades: each one's texel size (local units), and the camera view depths (local units,
    // along lsCameraForward from the eye) where cascade i covers [lsSplits[i], lsSplits[i + 1]].
    std::array<double, kMaxFaces> cascadeTexel{};
    std::array<double, kMaxFaces + 1> lsSplits{};
    double fovYDeg = 0.0;
    glm::dvec3 lsPosition{0.0}, lsDirection{0.0, -1.0, 0.0};
    double cosOuter = -1.0;  // spot
    // Rect and disk lights: the unit normal of the side they emit on; behind it nothing is lit
    // (the oracle's V = 0). Zero for lights that emit every way.
    glm::dvec3 lsEmitNormal{0.0};
    glm::dmat4 clipFromLocal(int face) const {
        return clipFromView[size_t(face)] * viewFromLocal[size_t(face)];
    }
};

// What cascades need of the camera: its frame in local space and the depth range it sees.
struct CascadeView {
    glm::dvec3 lsEye{0.0}, forward{0.0, 0.0, -1.0}, right{1.0, 0.0, 0.0}, up{0.0, 1.0, 0.0};
    double tanHalfVfov = 0.5, aspect = 1.0;
    // The nearest and farthest view depth of a surface the camera sees (local units).
    double lsNearest = 0.0, lsFarthest = 1.0;
};

struct CascadeSettings {
    int count = 4;
    double lambda = 0.5;  // practical split: 0 uniform, 1 logarithmic
    // Bounding-sphere fit with texel snapping (a cascade's texels stay put as the camera moves),
    // else each slice's tight box in the light's frame (sharper, but it shimmers).
    bool snap = true;
};

// The practical split scheme (Zhang et al. 2006): split i of n between near and far is
// lambda * near (far / near)^(i / n) + (1 - lambda) (near + (far - near) i / n).
double practicalSplit(double near, double far, int i, int n, double lambda);

// The view's depth range rounded outwards to powers of two (far up, near down, near at least
// far / 2^12), so that splits do not move with every small camera motion: only the texel snap
// differs between the two fits.
void cascadeRange(const CascadeView& view, double& lsNear, double& lsFar);

// A directional light's cascades: orthographic maps sharing the light's view (and the scene's
// depth range, so every occluder is in each), each fitted to its slice of the camera's frustum.
LightCamera fitCascades(const Light& light, const Bounds3d& lsBounds, int resolution,
                        const CascadeView& view, const CascadeSettings& settings);

// `lsReceivers` (optional, directional lights only): fit the map's x and y to these bounds (the
// receivers the camera sees) instead of the whole scene's; depth still spans the whole scene, so
// every occluder between the light and those receivers is in the map. Exact: along parallel rays
// only occluders inside the receivers' footprint can shadow them.
LightCamera fitLightCamera(const Light& light, const LocalFrame& frame, const Bounds3d& lsBounds,
                           int resolution, const Bounds3d* lsReceivers = nullptr);

// One shadow-map camera of a light in world space, as `shadow-oracle view` hands it to other
// renderers (docs/external.md): viewFromWorld is rigid (world units), clipFromView maps depth to
// [0, 1] as the raster path's maps do (glClipControl GL_ZERO_TO_ONE), y up.
struct LightSpaceFace {
    std::string face;  // "map"; a cube's "+x", "-x", "+y", "-y", "+z", "-z" (GL face order)
    glm::dmat4 viewFromWorld{1.0}, clipFromView{1.0};
};

// fitLightCamera in world space: the scene's frame is LocalFrame::fit(scene.wsBounds), as the
// raster path's GpuScene; `lsReceivers` as for fitLightCamera.
std::vector<LightSpaceFace> lightSpaceFaces(const Light& light, const Bounds3d& wsSceneBounds,
                                            const Bounds3d* lsReceivers);

// The shaders' defines for a light camera (shadow_map.frag): LIGHT_ORTHO, LIGHT_SPOT (a
// perspective map) or LIGHT_CUBE, and with cascades LIGHT_ORTHO and CASCADES n.
std::string lightCameraDefines(const LightCamera& cam);
// The same for the camera the light's kind takes (raster_compare/gl/lights/), before it is fitted.
std::string lightCameraDefines(const Light& light);

// The width of an area light as the soft-shadow approximations take it (pcss, plateaus): the side
// of a square of its area (rect: sqrt(|u x v|); disk and sphere: r sqrt(pi)), world units; 0 for
// point, spot and directional lights.
double lightWidth(const Light& light);

}  // namespace so
