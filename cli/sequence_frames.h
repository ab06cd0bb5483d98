// --frame K and --frames A:B of the commands that take a frame of a scene's sequence (trace, view,
// export; docs/cli.md): parsed and checked against the scene's sequence, one-line InputErrors
// naming the flag.
#pragma once

#include <optional>
#include <string>
#include <utility>

#include "core/scene.h"

namespace so {

// A frame number: decimal digits only (`form` says what was expected, e.g. "K (e.g. 8)").
int frameNumber(const std::string& text, const std::string& whole, const char* flag,
                const char* form);

// The first and last frame of --frame K (`frame`) or --frames A:B (`frames`; at most one of the
// two is not empty), checked against `scene`'s sequence (the file `scenePath`).
std::pair<int, int> sequenceFrameRange(const Scene& scene, const std::string& scenePath,
                                       const std::string& frame, const std::string& frames);

// --frame K of view and export: the scene posed at frame K (core/scene_pose.h); nothing when
// `frame` is empty (the scene as loaded).
std::optional<Scene> sceneAtFrameOption(const Scene& scene, const std::string& scenePath,
                                        const std::string& frame);

}  // namespace so
