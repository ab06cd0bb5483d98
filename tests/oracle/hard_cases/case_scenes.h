// The scenes of the hard cases (docs/hard-cases.md), shared by the per-case tests and by the
// far-from-the-origin test, which runs every one of them translated and scaled.
#pragma once

#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "core/scene.h"

namespace so::test::hard {

// Case 1: a plane through the origin (axis-aligned, or tilted), spanned by the dyadic edges u, v
// (normal: cross(u, v), towards the camera), lit from n.l = 1e-1 down to 1e-5, at exactly 0 and
// below the horizon, by directional, point and (sampled, with "penumbra") rect lights. Nothing
// occludes: V must be exactly 1 where n.l > 0 and 0 where n.l <= 0.
struct GrazingLight {
    std::string name;
    bool sampledRect = false;  // the sampled rect light (else directional or point)
    double cosine = 0.0;       // the nominal n.l (for point and rect lights, at the plane's centre)
};
struct GrazingScene {
    Scene scene;
    glm::dvec3 wsNormal{0.0};  // unit, the lit side
    std::vector<GrazingLight> lights;
};
GrazingScene makeGrazingScene(bool tilted, int size);
inline constexpr double kGrazingCosines[] = {1e-1, 1e-2, 1e-3, 1e-4, 1e-5, 0.0, -1e-5, -1e-1};

// Case 2: the floor y = 0, [-12, 12]^2, and the box [-1, 1] x [gap, 2 + gap] x [-1, 1] (gap:
// gapRelative of the scene's size, rounded to 2^-30), a point light at (3.5, 4, 2.5). The wide
// camera sees the box's foot on the shadow side; the zoomed one frames the foot's edge x = -1
// (z near 0) over about 40 gaps (the resting box: over 0.05 units).
struct ContactScene {
    Scene scene;
    glm::dvec3 boxLo{0.0}, boxHi{0.0}, wsLight{0.0};
    double gap = 0.0;
    double viewWidth = 0.0;  // zoomed: the width of the framed floor, world units
};
ContactScene makeContactScene(double gapRelative, bool zoomed, int size);
inline constexpr double kContactGaps[] = {0.0, 1e-3, 1e-5, 1e-7};

// Case 3, image level: a closed mesh (cube or icosphere, rotated by a seeded random rotation)
// over a floor, lit by a point light, seen from above.
struct ClosedMeshScene {
    Scene scene;
    glm::dvec3 wsLight{0.0};
};
ClosedMeshScene makeClosedMeshScene(bool icosphere, uint64_t seed, int size);

}  // namespace so::test::hard
