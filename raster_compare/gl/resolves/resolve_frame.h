// What every resolve (resolve.h) of one light shares: its full-screen targets, the frame before
// from the caller's TemporalState uploaded once a frame, and the one reprojection every history
// uses (resolve_frame.glsl): a pixel's local point moved by its mesh's exact motion into the frame
// before's local frame (per mesh, from TemporalState::wsPreviousFromWs) and projected by that
// frame's unjittered camera.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "raster_compare/gl/context/gl_object.h"
#include "raster_compare/gl/context/gl_program.h"
#include "raster_compare/gl/resolves/resolve.h"
#include "raster_compare/gl/time/temporal_state.h"

namespace so {

class ResolveFrame {
  public:
    explicit ResolveFrame(const ResolveSetup& setup);

    int width() const { return W_; }
    int height() const { return H_; }
    // A program of one pass: fullscreen.vert, then resolve_frame.glsl and `sources`, with `defines`
    // and the texel bytes of what it reads (VISIBILITY_, POSITION_, NORMAL_, HISTORY_TEXEL_BYTES).
    // Samplers: 0 the light's V, 1 position, 2 normal (w: id.mesh), 3 and 4 the frame before's
    // history and positions.
    GlProgram program(const std::string& defines, const std::vector<const char*>& sources) const;
    // The frame before (null: none of this size, or no state), read once a frame.
    const ResolvedFrame* previous();
    // Binds the inputs on their units and, where there is a frame before, uploads it (once) and
    // sets the reprojection (u_haveHistory, u_prevClipFromLocal, u_prevLsEye, u_prevPixelScale, the
    // per-mesh motions on SSBO binding 0).
    void bindInputs(const GlProgram& p);
    // Draws `p` full screen into the history target (location 0) and resolved V (location 1), then
    // copies resolved V into the light's target, which it leaves bound.
    void draw(const GlProgram& p);
    // The frame before's history texture (for a pass that samples it with a sampler of its own).
    GLuint previousHistoryTexture() const { return prevHistory_.get(); }
    // Keeps this frame's history target, positions and camera in the state (if any).
    void keep(int historyFrames);
    uint64_t memoryBytes() const;

  private:
    const ResolveSetup setup_;
    int W_, H_;
    bool loaded_ = false, uploaded_ = false;
    const ResolvedFrame* before_ = nullptr;
    GlTexture history_, resolvedV_, prevHistory_, prevPosition_;
    GlFramebuffer fbo_;
    GlBuffer motion_;
};

// A light's resolve of one full-screen pass over a ResolveFrame (history's and taa's): its program
// (`sources` after resolve_frame.glsl, with `defines`), timed and counted as `pass`.
class OnePassResolve : public LightResolve {
  public:
    OnePassResolve(const ResolveSetup& setup, std::string pass, const std::string& defines,
                   const std::vector<const char*>& sources);
    void resolve(PassClock& clock) override;
    void keep() override { frame_.keep(frames_ == 0 ? 1 : frames_); }
    int historyFrames() const override { return frames_; }
    uint64_t memoryBytes() const override { return frame_.memoryBytes(); }

  protected:
    // What the pass reads beyond the frame's inputs (units 5 and up): bound after bindInputs,
    // unbound after the draw.
    virtual void bindOwn() {}
    virtual void unbindOwn() {}
    GLuint program() const { return program_.get(); }
    const ResolveFrame& frame() const { return frame_; }

  private:
    ResolveFrame frame_;
    std::string pass_;
    GlProgram program_;
    int frames_ = 0;
};

}  // namespace so
