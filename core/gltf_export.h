// The scene as one binary glTF 2.0 file for other renderers (`shadow-oracle export`,
// docs/export.md): every mesh in world space, the camera, the lights as KHR_lights_punctual with
// the area lights' true shapes in their extras. Written with tinygltf; the same scene and options
// give the same bytes.
#pragma once

#include <string>
#include <vector>

#include "core/scene.h"

namespace so {

// The glb's export format (docs/export.md): asset.extras.shadow_oracle.format_version.
inline constexpr int kGlbExportFormat = 1;

struct GlbExportOptions {
    CameraDesc camera;    // the view's camera (its width and height give the aspect ratio)
    double zNear = 0.01;  // the view's near and far planes (view.json's camera.near, far)
    double zFar = 100.0;
    std::string sourcePath;  // the scene file as the user named it, for asset.extras and errors
};

// The glb's bytes. Throws InputError naming opts.sourcePath for what glTF cannot hold (an alpha
// texture without its source image bytes, more than 4 GiB of buffer data).
std::vector<unsigned char> sceneToGlb(const Scene& scene, const GlbExportOptions& opts);

}  // namespace so
