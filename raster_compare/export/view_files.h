// The exact view another renderer must reproduce, so that its shadow images can be judged pixel
// for pixel (docs/external.md): view.json (camera and light matrices in the OpenGL and Vulkan
// conventions, lights, geometry) and gbuffer.exr (the oracle's primary hits). Written by
// `shadow-oracle view` and, beside the glb, by `shadow-oracle export`.
#pragma once

#include <filesystem>
#include <string>

#include "core/scene.h"
#include "oracle/oracle.h"

namespace so {

inline constexpr int kViewFormat = 1;

// The camera's near and far planes that view.json records (docs/external.md): far just beyond the
// farthest corner of the scene's bounds, near just before the bounds (at least far / 10^5).
void viewDepthRange(const Camera& camera, const Bounds3d& wsBounds, double& near, double& far);

struct ViewFiles {
    std::filesystem::path viewJson, gbufferExr;
};

// Traces the primary rays of effectiveCamera(scene, oracle) and writes `outDir`/view.json and
// `outDir`/gbuffer.exr (the folder must exist). `scenePath` is the scene as the user named it.
// An InputError names a file that cannot be written.
ViewFiles writeViewFiles(const Scene& scene, const std::string& scenePath,
                         const OracleOptions& oracle, const std::filesystem::path& outDir);

// Writes `bytes` to `path`, or an InputError naming it: "cannot be written (WHY)".
void writeFileBytes(const std::filesystem::path& path, const std::string& bytes);

}  // namespace so
