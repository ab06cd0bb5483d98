// What the ray-traced family (techniques/raytraced.cpp) hands one light's denoiser: the frame's
// full-screen targets, its G-buffer, the programs of its passes and the history across a
// sequence's frames. The light traces the rays into `raw`, its denoiser (denoiser.h) filters them
// into one of the targets, and the light resolves that target's V into its own.
//
// The history lives across the renders of a sequence (RasterOptions::frameIndex): frame f reads
// what frame f - 1 left, so a repeated render of a frame (warm-up, timed frames) gives the same
// image. The history follows the camera and every mesh's exact motion (the caller's temporal
// state, time/temporal_state.h, which also keeps the store).
#pragma once

#include <cstdint>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include <glm/mat4x4.hpp>

#include "core/local_frame.h"
#include "raster_compare/gl/context/gl_object.h"
#include "raster_compare/gl/context/gl_program.h"

namespace so {

struct Light;
class GpuScene;
class CameraPass;
class TemporalState;

// What frame f of a light left for frame f + 1, on the CPU (GL objects do not outlive a render).
struct RayHistoryFrame {
    int width = 0, height = 0;
    std::vector<float> history;     // RGBA, GL row order: V, first and second moments, length
    std::vector<float> lsPosition;  // RGBA, the camera pass's positions in `frame`
    // A denoiser's own state beyond `history` (rtg's variation and sample-count caches): RGBA
    // each, in the order keepHistory was given them.
    std::vector<std::vector<float>> extra;
    glm::dmat4 clipFromLocal{1.0};
    LocalFrame frame;
};

// The frames kept per light: frame f and f - 1, so that every render of frame f reads f - 1.
class RayHistoryStore {
  public:
    std::optional<RayHistoryFrame> before(const std::string& light, int frameIndex, int width,
                                          int height) const;
    void keep(const std::string& light, int frameIndex, RayHistoryFrame frame);

  private:
    mutable std::mutex mutex_;
    std::map<std::string, std::map<int, RayHistoryFrame>> frames_;
};

// A full-screen target of its own.
struct ScreenTarget {
    ScreenTarget(GLenum format, int width, int height);
    GlTexture texture;
    GlFramebuffer fbo;
};

// The target a denoiser leaves its result in (its texel bytes are every pass's
// RESULT_TEXEL_BYTES).
enum class RayTarget { Raw, Accum, Filter };

// One light's targets and passes. Every texture is in GL's row order.
class RayFrame {
  public:
    // `temporal`: where the meshes' motion since the frame before is (null: nothing moved).
    RayFrame(const Light& light, const GpuScene& scene, const CameraPass& camera, int frameIndex,
             RayHistoryStore& store, RayTarget result, const TemporalState* temporal = nullptr);

    const Light& light() const { return light_; }
    const GpuScene& scene() const { return scene_; }
    const CameraPass& camera() const { return camera_; }
    int width() const { return W_; }
    int height() const { return H_; }
    int frameIndex() const { return frameIndex_; }

    // A program of one pass: `pass` and `defines` defined, the targets' texel bytes defined
    // (RAW_, ACCUM_, FILTER_, TILE_, RESULT_TEXEL_BYTES and the camera pass's), then
    // denoisers/ray_frame.glsl and `sources`. Its samplers on fixed units: 0 the pass's input
    // (u_raw, u_accum, u_filter, u_result), 1 position, 2 normal, 3 and 4 the previous frame's
    // history and positions, 5 ffx's tiles.
    GlProgram program(const char* pass, const std::string& defines,
                      const std::vector<const char*>& sources) const;
    // A full-screen triangle drawn by `p` into `target`.
    void draw(const ScreenTarget& target, const GlProgram& p) const;
    // The temporal passes' inputs: whether frame f - 1 left a history of this size (u_haveHistory);
    // if so it is uploaded into prevHistory and prevPosition and `p`'s reprojection set
    // (u_prevScale, u_prevClipFromLocal, and per mesh the motion into the frame before's local
    // frame on SSBO binding 0, ray_frame.glsl's previousLocal). Binds raw, the G-buffer and the two
    // previous targets on units 0 to 4.
    // The store is read and the textures uploaded once a frame, however many passes bind them.
    void bindHistory(const GlProgram& p);
    // What frame f - 1 left (null: nothing of this size), read from the store once a frame.
    const RayHistoryFrame* previous();
    // What the next frame reprojects: accum's moments and length, with V from `firstLevel` (SVGF
    // feeds the first a-trous level back) or accum's own (0); and each of `extra` (RGBA32F
    // textures of the frame's size, read back as RGBA) as RayHistoryFrame::extra.
    void keepHistory(GLuint firstLevel, const std::vector<GLuint>& extra = {});
    // The GL memory of the targets.
    uint64_t memoryBytes() const;

  private:
    const Light& light_;
    const GpuScene& scene_;
    const CameraPass& camera_;
    int frameIndex_;
    RayHistoryStore& store_;
    RayTarget result_;
    const TemporalState* temporal_;
    GlBuffer motion_;  // per mesh, ray_frame.glsl's u_prevLocalFromLocal
    int W_, H_;
    bool loaded_ = false, uploaded_ = false;
    std::optional<RayHistoryFrame> before_;

  public:
    // raw: V of this frame's rays and their blockers' mean distance (RG32F); accum: the temporal
    // accumulation, V, its first two moments and the history's length (RGBA32F); filterA and
    // filterB: V and its variance, filtered back and forth (RG32F); prevHistory and prevPosition:
    // frame f - 1's accumulation and positions (RGBA32F).
    ScreenTarget raw, accum, prevHistory, prevPosition, filterA, filterB;
    // ffx: one texel per 8 x 8 tile (R32F), its tile classification.
    int tilesW, tilesH;
    ScreenTarget tiles;
    // This frame's G-buffer read back (RGBA32F, GL row order): the rays' origins.
    std::vector<float> position, normal;
};

}  // namespace so
