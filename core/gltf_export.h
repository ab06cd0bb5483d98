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

// The outer half-angle (radians) of the spot stand-in for a rect or disk light: the narrowest cone
// around its emitting normal that holds every corner of the scene's bounds in front of it, between
// 1 and 85 degrees (a spot's shadow map is a perspective frustum, which cannot reach 90).
double standInConeRad(const Light& light, const Bounds3d& wsBounds);

// The diameter of the disk with the area light's emitting area seen face-on: rect
// 2 sqrt(|u x v| / pi), disk and sphere 2 radius. The one size a PCSS-like mode takes.
double areaLightSize(const Light& light);

}  // namespace so
