// Lights moving on a sequence's clock (scene_format 5, `light_paths`, docs/scene-format.md#light-
// paths): reading the key and posing a light at a time. core/scene_pose.h poses whole scenes.
#pragma once

#include <vector>

#include "core/json_reader.h"
#include "core/scene.h"

namespace so {

// `light_paths`: {"LIGHT": {"keyframes": [{"t": T, "position": [...], "direction": [...]}, ...],
// "interpolation": "linear" | "catmull-rom"}, ...}, with camera_path's rules (at least 2 keys, t
// strictly increasing, at most maxPathKeyframes). Every key of a path sets the same fields, which
// the light's kind must take (LightKind::pathMovesPosition, pathTurnsDirection). Errors go through
// r, naming the field ("light_paths.sun.keyframes[1].direction").
std::vector<LightPath> parseLightPaths(const json& j, const JsonReader& r, const LoadLimits& limits,
                                       const std::vector<Light>& lights);

// `light` at t seconds: clamped to the keys' range, interpolated as the path says (a direction
// renormalised; where a spline would pass through zero, the nearer key's). A position moves the
// light rigidly: its centre goes there and an area light's shape follows.
Light lightAt(const LightPath& path, const Light& light, double t);

}  // namespace so
