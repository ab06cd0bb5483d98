#include "core/scene_pose.h"

#include <cstdio>

#include "core/camera_path.h"

namespace so {

// Interface first, filled in by the animation work (issue 52): so far only the camera moves.

double sequenceTime(const Sequence& sequence, int frame) { return double(frame) / sequence.fps; }

bool sceneMoves(const Scene& scene) { return scene.sequence && scene.cameraPath; }

Scene sceneAtTime(const Scene& scene, double t) {
    Scene posed = scene;
    if (!sceneMoves(scene)) return posed;
    posed.camera = cameraAt(*scene.cameraPath, scene.camera, t);
    posed.sequence.reset();
    posed.cameraPath.reset();
    char suffix[64];
    std::snprintf(suffix, sizeof suffix, "@t=%a", t);
    posed.contentHash += suffix;
    return posed;
}

glm::dmat4 meshMotion(const Scene&, size_t, double, double) { return glm::dmat4(1.0); }

}  // namespace so
