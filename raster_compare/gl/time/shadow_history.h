// A shadow-only history (docs/techniques.md#temporal), on the CPU: the reference of
// resolve=history, which resolves/history.glsl runs on the GPU step for step
// (tests/gl/resolve_history_test.cpp holds the two together). Each frame, the history of the
// light's V is reprojected into the new frame through the known motion (the camera's, and each
// mesh's rigid motion, core/scene_pose.h's meshMotion), optionally clamped to the new frame's
// neighbourhood, and blended: resolved = weight * history + (1 - weight) * current. Pixels whose
// history does not land on the same mesh and surface (disocclusion, off screen) start again from
// the current V.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "core/image.h"
#include "core/scene.h"

namespace so {

struct HistorySettings {
    double weight = 0.9;  // the history's share of each resolved frame; 0: each frame on its own
    bool clamp = true;    // neighbourhood clamping of the history against ghosting
};

// One frame as the history sees it: the raster image (its geometry channels P, id.mesh and A, and
// the light's V), the camera it was rendered with and its time on the sequence's clock.
struct HistoryFrame {
    const ChannelImage* image = nullptr;
    CameraDesc camera;
    double t = 0.0;
};

// The history of one technique and one light across a sequence's frames.
class ShadowHistory {
  public:
    ShadowHistory(HistorySettings settings, std::string light);
    // The current frame's V of the light resolved with the history (width * height, top row
    // first), kept with the frame's geometry as the next frame's history. The first frame is its
    // own V, and so is every pixel that missed, was off screen or hidden in the previous frame
    // (the previous pixel it lands in saw another mesh, or the same mesh elsewhere: a position
    // more than half a pixel's footprint away, plus 4 footprints per pixel of distance from that
    // pixel's centre for oblique surfaces), and every frame with weight 0. Elsewhere: history = the
    // previous resolved V at the point's previous position (meshMotion, then the previous camera),
    // bilinear over the matching texels; with clamp, clamped to [min, max] of the current V over
    // the 3x3 pixels around that hit; resolved = weight * history + (1 - weight) * current.
    // Deterministic, one thread. `image` needs the channels A, P.*, id.mesh (world positions, as
    // raster.exr holds them) and the light's V. `scene` is the scene with its motion (not a posed
    // frame): meshMotion reads it.
    std::vector<float> resolve(const Scene& scene, const HistoryFrame& current);

  private:
    // The previous resolved V at image position imagePos of the previous frame (pixel units,
    // (0,0) its top-left corner): bilinear over the texels that saw mesh `mesh` within a tolerance
    // of wsPrevious (the point where it stood then); none when off screen or when the pixel it
    // falls in does not match.
    std::optional<float> sample(const glm::dvec2& imagePos, long mesh,
                                const glm::dvec3& wsPrevious) const;
    // meshMotion(scene, mesh, t, t_), computed once per mesh and frame.
    const glm::dmat4& motionToPrevious(const Scene& scene, size_t mesh, double t);

    HistorySettings settings_;
    std::string light_;
    // The previous frame: its resolved V, geometry, camera and time (none before the first).
    std::vector<float> resolved_;
    ChannelImage geometry_;
    CameraDesc camera_;
    double t_ = 0.0;
    bool have_ = false;
    std::vector<glm::dmat4> motions_;  // this frame's motion per mesh, where motionKnown_
    std::vector<char> motionKnown_;
};

}  // namespace so
