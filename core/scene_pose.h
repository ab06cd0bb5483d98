// A scene at one moment of its sequence (scene_format 5, docs/scene-format.md#sequence): the glTF
// animations' rigid node motion applied to the meshes, the lights moved along their light_paths,
// and the camera along camera_path, all on the sequence's clock in seconds. What comes out is an
// ordinary static Scene, so the oracle, --verify and every technique see a frame as they see any
// scene; the motion between two moments (for reprojecting a history) comes from meshMotion.
#pragma once

#include <glm/mat4x4.hpp>

#include "core/scene.h"

namespace so {

// Frame `frame`'s time in seconds: frame / fps.
double sequenceTime(const Sequence& sequence, int frame);

// Whether anything in the scene moves with time: an animated mesh, a light path, or a camera path
// in a scene with a sequence.
bool sceneMoves(const Scene& scene);

// The scene as it stands at `t` seconds: every animated mesh moved rigidly (wsPositions, wsBounds
// and stats recomputed), every light with a light path moved, and, in a scene with a sequence and
// a camera_path, the camera placed by the path at t (camera_path.h's cameraAt). The result has no
// sequence, animation or paths left (it is static); its contentHash is the scene's extended by t
// when anything moves, so that each frame's oracle is cached on its own. A scene that does not
// move comes back unchanged.
Scene sceneAtTime(const Scene& scene, double t);

// The rigid motion of mesh `mesh` (an index into scene.meshes) from time `tFrom` to `tTo`: maps a
// world point on the mesh as posed at tFrom to where that point is at tTo. Identity for a mesh
// that does not move.
glm::dmat4 meshMotion(const Scene& scene, size_t mesh, double tFrom, double tTo);

}  // namespace so
