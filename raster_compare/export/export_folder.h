// `shadow-oracle export` (docs/export.md): the scene as a folder any engine can load. scene.glb
// (core/gltf_export.h), view.json and gbuffer.exr as `view` writes them (view_files.h), and
// scene.scene.json, a scene file that loads scene.glb with the scene's lights, camera and
// effects, so the folder is itself a scene the oracle traces.
#pragma once

#include <filesystem>
#include <string>

#include "core/scene.h"
#include "oracle/oracle.h"

namespace so {

struct ExportedFiles {
    std::filesystem::path glb, sceneFile, viewJson, gbufferExr;
};

// Writes the folder `outDir` (created with its parents if missing) for the view of
// effectiveCamera(scene, oracle): oracle.width and .height override the scene camera's size as
// in `view`, oracle.threads and .progress drive the primary rays of gbuffer.exr. `scenePath` is
// the scene as the user named it. An InputError names the folder or file that cannot be written.
ExportedFiles exportScene(const Scene& scene, const std::string& scenePath,
                          const OracleOptions& oracle, const std::filesystem::path& outDir);

}  // namespace so
