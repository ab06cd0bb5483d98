// A scene file (docs/scene-format.md) for a scene already loaded: what `shadow-oracle export`
// writes beside its glb so that the exported folder is itself a scene the oracle traces.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "core/scene.h"

namespace so {

// The scene file whose one geometry entry is `geometryFile` (relative to the scene file, holding
// the scene's meshes already in world space), with the scene's lights, camera path and effects
// and `camera` (the view's, at its width and height). Values are the loaded ones (directions
// normalised), written with full double precision.
// One light as the scene format spells it: only the keys its type takes, values as loaded (also
// view.json's lights, raster_compare/export/view_files.h).
nlohmann::json sceneLightJson(const Light& light);

nlohmann::json sceneFileJson(const Scene& scene, const CameraDesc& camera,
                             const std::string& geometryFile);

}  // namespace so
