// Scenes built in code for the oracle tests, with the exact geometry kept beside them so each
// test can compute its closed-form answer in double.
#pragma once

#include <glm/vec3.hpp>

#include "core/image.h"
#include "core/scene.h"
#include "lambert.h"
#include "oracle/oracle.h"

namespace so::test {

// A parallelogram centred at c spanned by the full edge vectors u and v, split into n x n cells
// (2 triangles each) so shadow rays cross many shared edges.
MeshPrimitive makeGrid(const glm::dvec3& c, const glm::dvec3& u, const glm::dvec3& v, int n,
                       const std::string& name);
// An axis-aligned closed box, outward-facing triangles.
MeshPrimitive makeBox(const glm::dvec3& lo, const glm::dvec3& hi, const std::string& name);

// Receiver: the plane y = 0, [-8, 8]^2 (mesh 0). Occluder: the square y = 2, [-1.5, 1]x[-1, 1.25]
// (mesh 1). Lights: a point, a spot and a directional light above. All coordinates are dyadic so
// a power-of-two scale or a dyadic translation is exact.
struct SquareOccluderScene {
    static constexpr double kOccluderY = 2.0;
    static constexpr double kX0 = -1.5, kX1 = 1.0, kZ0 = -1.0, kZ1 = 1.25;
    Scene scene;
};
SquareOccluderScene makeSquareOccluderScene(int width, int height);

// A rect light 2 x 1.5 at height 4 emitting down, a 2 x 2 square occluder at height 1.5, the
// floor: the closed-form scene of lambert.h (exactRectLightRectOccluderV).
struct PenumbraScene {
    AxisRect light{4.0, -0.5, 1.5, -0.5, 1.0};
    AxisRect occluder{1.5, -1.0, 1.0, -1.0, 1.0};
    Scene scene;
};
PenumbraScene makePenumbraScene(int width, int height);

// A long receiver (the ground, mesh 0) seen from near it toward the horizon, a low sun ("sun"),
// twelve posts casting long shadows: the adaptive map's scene (its texel density follows the view).
Scene makeGroundPostsScene(int width, int height);

// Applies p -> p * scale + translate to every position in the scene (meshes, camera, lights), and
// scales the area lights' extents.
Scene transformScene(const Scene& scene, double scale, const glm::dvec3& translate);

// Runs the oracle quietly.
ChannelImage runQuiet(const Scene& scene, int threads = 0);

// A rect light: centre, full edges u and v (it emits towards cross(u, v)).
Light makeRectLight(const std::string& name, const glm::dvec3& center, const glm::dvec3& u,
                    const glm::dvec3& v);
// The scene's camera from eye to target, vfov degrees, width x height pixels.
void aimCamera(Scene& scene, const glm::dvec3& eye, const glm::dvec3& target, double vfovDeg,
               int width, int height);

}  // namespace so::test
