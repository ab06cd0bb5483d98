// Sampling a scene's camera path (scene_format 2, docs/scene-format.md#camera-path) into the
// cameras of compare --frames-path's frames.
#pragma once

#include <vector>

#include "core/scene.h"

namespace so {

// `frames` (>= 2) cameras at t evenly spaced from the first keyframe's t to the last one's, both
// included: frame i is at t0 + i (tN - t0) / (frames - 1), so the first and last frames are the
// first and last keyframes exactly. Eye, target and up follow the path's interpolation (linear, or
// Catmull-Rom through every keyframe with tangents from the neighbours' finite differences over
// their t); vfov_deg is always linear (a spline could leave (0, 180)). Width and height are
// base's, and so are up and vfov_deg where a keyframe leaves them out. Throws InputError
// (path.file, field camera_path) when an interpolated pose degenerates (eye reaching target, up
// parallel to the view), which the keyframes' own checks cannot rule out.
std::vector<CameraDesc> sampleCameraPath(const CameraPath& path, const CameraDesc& base,
                                         int frames);

// The pose at parameter t, clamped to the path's range (the same rules as above).
CameraDesc cameraAt(const CameraPath& path, const CameraDesc& base, double t);

}  // namespace so
