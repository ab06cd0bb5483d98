// The temporal state a caller owns across the frames it renders (docs/techniques.md#resolve): a
// sequence's frames (compare --sequence), still frames (compare --converge) or a camera path. The
// caller says, before each frame, its index and where each mesh's points of this frame stood in
// the frame before (core/scene_pose.h's meshMotion); the renderer's resolves (resolves/resolve.h)
// keep here, per technique and light, what the next frame reprojects, and the ray-traced
// denoisers keep their history in the same state. A render given no state is a cold start: every
// resolve sees no history and says so (history_frames 0).
#pragma once

#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "core/local_frame.h"
#include "raster_compare/gl/denoisers/ray_frame.h"

namespace so {

// What one resolve of one light left for the next frame, on the CPU (GL objects do not outlive a
// render). Every image in GL's row order, width * height texels of RGBA.
struct ResolvedFrame {
    int width = 0, height = 0;
    std::vector<float> history;     // the resolve's own history texels
    std::vector<float> lsPosition;  // the camera pass's positions, w: id.mesh + 1 (0: no hit)
    // The frame's camera, unjittered (what the next frame reprojects into), in its local frame.
    glm::dmat4 clipFromLocal{1.0};
    glm::dvec3 lsEye{0.0}, lsForward{0.0, 0.0, -1.0};
    double pixelScale = 0.0;  // a pixel's size per unit of distance
    LocalFrame frame;
    int historyFrames = 0;  // how many frames this history holds (this one included)
};

class TemporalState {
  public:
    // Before frame `frameIndex` (0, 1, ...): per mesh (Scene::meshes' order), the world transform
    // from a point of this frame to where it stood in the frame before (identity where it did not
    // move); empty: nothing moved (or the first frame).
    void beginFrame(int frameIndex, std::vector<glm::dmat4> wsPreviousFromWs = {});
    int frameIndex() const { return frameIndex_; }
    // The mesh's motion since the frame before (identity where none was given).
    glm::dmat4 wsPreviousFromWs(size_t mesh) const;

    // What frame frameIndex() - 1 left for (owner, light) at this size; null: a cold start.
    const ResolvedFrame* before(const void* owner, const std::string& light, int width,
                                int height) const;
    // Keeps this frame's; frames older than the one before are dropped. Every render of a frame
    // (warm-up, timed, counted) reads the same frame before, so they give the same image.
    void keep(const void* owner, const std::string& light, ResolvedFrame frame);
    // The ray-traced denoisers' history of `owner` (denoisers/ray_frame.h).
    RayHistoryStore& rayHistory(const void* owner);

  private:
    int frameIndex_ = 0;
    std::vector<glm::dmat4> motion_;
    mutable std::mutex mutex_;
    std::map<std::pair<const void*, std::string>, std::map<int, ResolvedFrame>> frames_;
    std::map<const void*, RayHistoryStore> rays_;
};

// Per mesh (`meshes` of them, at least one entry), the matrix from this frame's local point (local
// frame `now`) to where it stood in the frame before (local frame `before`): the mesh's motion in
// `state` (none: identity) between the two frames' local frames; float, column-major, 16 a mesh:
// what a GPU reprojection reads per mesh (SSBO binding 0).
std::vector<float> previousFromLocalPerMesh(const TemporalState* state, size_t meshes,
                                            const LocalFrame& now, const LocalFrame& before);

}  // namespace so
