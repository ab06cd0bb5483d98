// temporal_flicker_rate (docs/metrics.md#temporal-flicker): how often a technique's shadow flips
// between consecutive frames of a camera path at a surface point where the oracle's does not.
// Pure functions of images and cameras, so tests render (or make up) the frames themselves.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <glm/mat4x4.hpp>
#include <nlohmann/json.hpp>

#include "core/image.h"
#include "core/scene.h"

namespace so {

// One frame of a path: its camera and both images (docs/exr-channels.md: A, P.X/Y/Z, id.mesh,
// id.prim, NAME.V, NAME.cos, NAME.stderr for sampled area lights). Not owned.
struct TemporalFrame {
    CameraDesc camera;
    const ChannelImage* oracle = nullptr;
    const ChannelImage* raster = nullptr;
};

struct TemporalOptions {
    double rasterJump = 0.5;  // |dV| of the raster above this is a flip
    // A pixel is tracked only where its point lands within this many pixels (along x and along y)
    // of the centre of the previous frame's pixel (0.5: the nearest pixel, whatever the offset).
    // Two samples up to half a pixel apart straddle a stable but misplaced (aliased) shadow edge
    // often enough to look like flicker; within 1/8 pixel they see nearly the same surface point,
    // so what remains is the technique's own change (docs/metrics.md#temporal-flicker).
    double trackRadius = 0.125;
    // The oracle's own change allowed for a flip to count: 0 for exact (hard) lights; for sampled
    // area lights stderrFactor * sqrt(se_k^2 + se_k+1^2) + epsilon.
    double stderrFactor = 3.0;
    double epsilon = 1e-6;
};

// Frames k and k+1: pixel pairs tracked and those that flicker.
struct FramePairFlicker {
    size_t tracked = 0, flickering = 0;
};

struct TemporalFlicker {
    size_t tracked = 0, flickering = 0;
    std::vector<FramePairFlicker> pairs;  // pairs[k]: frames k and k+1
    // flickering / tracked; none when no pair was tracked.
    std::optional<double> rate() const;
    // The pair with the most flickering pixels (the first on ties); no pairs:
    // std::invalid_argument.
    size_t worstPair() const;
    void add(const FramePairFlicker& p);
    // "temporal_flicker_rate", "temporal_tracked_pairs", "temporal_flickering_pairs",
    // "temporal_frames" for a row of metrics.json.
    void addToJson(nlohmann::json& row) const;
};

// The known motion of the meshes between two frames (compare --sequence): prevFromNext[m] maps a
// world point of mesh m (id.mesh) as it stands in the next frame to where that point was in the
// previous one (core/scene_pose.h's meshMotion(scene, m, tNext, tPrev)). A mesh beyond its end
// does not move.
using MeshMotions = std::vector<glm::dmat4>;

// Tracks every pixel x of `next` that the oracle sees hit into `prev`: its world point P, moved
// back by its mesh's motion when `motion` is given, projected through prev's camera to the pixel
// x' holding it (x' = x when both cameras are equal and the mesh did not move). Tracked:
// x' inside, both pixels counted as computeLightMetrics counts (both images hit, the raster sees
// the oracle's mesh and triangle, facing the light) and on the same mesh and triangle in both
// frames. Flickering: the raster's V changes by more than rasterJump and the oracle's by no more
// than its tolerance. `mask`, if given, gets next's pixels: 1 tracked, 2 flickering, 0 neither.
FramePairFlicker compareFramePair(const TemporalFrame& prev, const TemporalFrame& next,
                                  const std::string& light, const TemporalOptions& options = {},
                                  std::vector<uint8_t>* mask = nullptr,
                                  const MeshMotions* motion = nullptr);

// Over all consecutive pairs of `frames` (at least 2 for any pair).
TemporalFlicker computeTemporalFlicker(const std::vector<TemporalFrame>& frames,
                                       const std::string& light,
                                       const TemporalOptions& options = {});

}  // namespace so
