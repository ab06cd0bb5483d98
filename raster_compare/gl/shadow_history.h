// A shadow-only history (docs/techniques.md#temporal): what a technique that builds its shadow over
// frames (temporal=on) resolves its jittered V with. Each frame, the history of the light's V is
// reprojected into the new frame through the known motion (the camera's, and each mesh's rigid
// motion, core/scene_pose.h's meshMotion), optionally clamped to the new frame's neighbourhood,
// and blended: resolved = weight * history + (1 - weight) * current. Pixels whose history does not
// land on the same mesh and surface (disocclusion, off screen) start again from the current V.
// Ray-traced shadows with a denoiser plug into the same reprojection.
#pragma once

#include <string>
#include <vector>

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
    // own V. `scene` is the scene with its motion (not a posed frame): meshMotion reads it.
    std::vector<float> resolve(const Scene& scene, const HistoryFrame& current);

  private:
    HistorySettings settings_;
    std::string light_;
    // The previous frame: its resolved V, geometry, camera and time (none before the first).
    std::vector<float> resolved_;
    ChannelImage geometry_;
    CameraDesc camera_;
    double t_ = 0.0;
    bool have_ = false;
};

}  // namespace so
