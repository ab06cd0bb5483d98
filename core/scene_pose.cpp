#include "core/scene_pose.h"

#include <cmath>
#include <cstdio>

#include <glm/matrix.hpp>

#include "core/camera_path.h"
#include "core/error.h"
#include "core/gltf_animation.h"
#include "core/light_path.h"

namespace so {

double sequenceTime(const Sequence& sequence, int frame) {
    return double(frame) / sequence.fps;
}

bool sceneMoves(const Scene& scene) {
    if (!scene.sequence) return false;
    if (scene.cameraPath || !scene.lightPaths.empty()) return true;
    for (const MeshPrimitive& m : scene.meshes)
        if (m.animation) return true;
    return false;
}

Scene sceneAtTime(const Scene& scene, double t) {
    Scene posed = scene;
    if (!sceneMoves(scene)) return posed;
    for (MeshPrimitive& mesh : posed.meshes) {
        if (!mesh.animation) continue;
        const glm::dmat4 wsFromLs = mesh.animation->worldAt(t);
        const std::vector<glm::dvec3>& ls = mesh.animation->lsPositions;
        for (size_t i = 0; i < ls.size(); ++i) {
            const glm::dvec3 p(wsFromLs * glm::dvec4(ls[i], 1.0));
            // Finite keys can still overflow (a huge scale times a huge translation): one line,
            // not a NaN that the bounds check below would not see.
            if (!(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z))) {
                char text[200];
                std::snprintf(text, sizeof text,
                              "at t = %.6g the animation moves vertex %zu of %s to a non-finite "
                              "place",
                              t, i, printable(mesh.name, 80).c_str());
                throwInputError(scene.path.string(), "animations", text);
            }
            mesh.wsPositions[i] = p;
        }
        mesh.animation.reset();
    }
    for (const LightPath& path : scene.lightPaths)
        for (Light& light : posed.lights)
            if (light.name == path.light) light = lightAt(path, light, t);
    posed.lightPaths.clear();
    if (scene.cameraPath) posed.camera = cameraAt(*scene.cameraPath, scene.camera, t);
    posed.sequence.reset();
    posed.cameraPath.reset();
    // Bounds, triangle and degenerate counts of the pose (a scale key may flatten a mesh); the
    // warnings of the load are the scene's and stay as they are.
    finalizeScene(posed);
    char suffix[64];
    std::snprintf(suffix, sizeof suffix, "@t=%a", t);
    posed.contentHash += suffix;
    return posed;
}

glm::dmat4 meshMotion(const Scene& scene, size_t mesh, double tFrom, double tTo) {
    if (!scene.sequence || mesh >= scene.meshes.size() || !scene.meshes[mesh].animation)
        return glm::dmat4(1.0);
    const MeshAnimation& animation = *scene.meshes[mesh].animation;
    const glm::dmat4 wsFrom = animation.worldAt(tFrom);
    // A pose that scales the mesh to nothing at tFrom shows no point to carry: only its place
    // moves.
    if (!(std::abs(glm::determinant(wsFrom)) > 0.0)) {
        glm::dmat4 shift(1.0);
        shift[3] = glm::dvec4(glm::dvec3(animation.worldAt(tTo)[3] - wsFrom[3]), 1.0);
        return shift;
    }
    return animation.worldAt(tTo) * glm::inverse(wsFrom);
}

}  // namespace so
