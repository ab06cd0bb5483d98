#include "case_scenes.h"
#include "core/lights/make_light.h"

#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>

#include "hard_scenes.h"
#include "test_scenes.h"

namespace so::test::hard {

namespace {

// The three lights of one nominal cosine c: toward `toLight` (unit, n.l = c), or, for c = 0,
// exactly in the plane (dyadic points on it), so that n.l is 0 in exact arithmetic.
void addGrazingLights(GrazingScene& g, int index, double c, const glm::dvec3& u,
                      const glm::dvec3& v) {
    const glm::dvec3 n = g.wsNormal;
    const glm::dvec3 t1 = glm::normalize(u), t2 = glm::normalize(glm::cross(n, t1));
    const double s = std::sqrt(1.0 - c * c);
    for (int az = 0; az < 2; ++az) {
        const glm::dvec3 t = az == 0 ? t1 : t2;
        // For c = 0 the direction must lie in the plane in double too: normalize(u) and
        // normalize(-v) do (their components are one rounded factor times small integers, and
        // scaling by a power of two is exact), t2 = n x t1 does not.
        const glm::dvec3 toLight =
            c == 0.0 ? (az == 0 ? glm::normalize(u) : glm::normalize(-v)) : c * n + s * t;
        const std::string tag = std::to_string(index) + "_" + std::to_string(az);
        g.scene.lights.push_back(directionalLight("dir_" + tag, -toLight));
        g.lights.push_back({"dir_" + tag, false, c});
        const glm::dvec3 wsPoint = c == 0.0 ? (az == 0 ? 32.0 * u : -32.0 * v) : 1024.0 * toLight;
        g.scene.lights.push_back(pointLight("pt_" + tag, wsPoint));
        g.lights.push_back({"pt_" + tag, false, c});
    }
    // A rect light parallel to the plane (its edges are u / 32 and -v / 32, so every corner is
    // exactly as high above the plane as its centre), emitting towards it.
    const Light rect = rectLight("rect_" + std::to_string(index),
                                 c == 0.0 ? 4.0 * u : 64.0 * (c * n + s * t1), u / 32.0, -v / 32.0);
    g.scene.lights.push_back(rect);
    g.lights.push_back({rect.name, true, c});
}

}  // namespace

GrazingScene makeGrazingScene(bool tilted, int size) {
    GrazingScene g;
    const glm::dvec3 u = tilted ? glm::dvec3(16, 8, 0) : glm::dvec3(16, 0, 0);
    const glm::dvec3 v = tilted ? glm::dvec3(0, 4, -16) : glm::dvec3(0, 0, -16);
    g.wsNormal = glm::normalize(glm::cross(u, v));
    g.scene.meshes.push_back(makeGrid({0, 0, 0}, u, v, 16, "plane"));
    const glm::dvec3 t1 = glm::normalize(u), t2 = glm::normalize(glm::cross(g.wsNormal, t1));
    g.scene.camera.wsEye = 14.0 * g.wsNormal + 3.0 * t1;
    g.scene.camera.wsTarget = {0, 0, 0};
    g.scene.camera.wsUp = t2;
    g.scene.camera.width = g.scene.camera.height = size;
    int index = 0;
    for (double c : kGrazingCosines) addGrazingLights(g, index++, c, u, v);
    g.scene.effects = {"hard", "penumbra"};
    // Positions on a 2^-20 grid: translations up to 2^32 stay exact. The c = 0 lights and the
    // rect edges are dyadic already.
    snapScene(g.scene, 20);
    return g;
}

ContactScene makeContactScene(double gapRelative, bool zoomed, int size) {
    ContactScene c;
    const double sceneSize = std::sqrt(24.0 * 24.0 * 2.0 + 4.0);
    c.gap = snap(gapRelative * sceneSize, 30);
    c.boxLo = {-1, c.gap, -1};
    c.boxHi = {1, 2 + c.gap, 1};
    c.wsLight = {3.5, 4.0, 2.5};
    Scene& s = c.scene;
    s.meshes.push_back(makeGrid({0, 0, 0}, {24, 0, 0}, {0, 0, -24}, 16, "floor"));
    s.meshes.push_back(makeBox(c.boxLo, c.boxHi, "box"));
    s.lights.push_back(pointLight("key", c.wsLight));
    s.camera.width = s.camera.height = size;
    if (!zoomed) {
        s.camera.wsEye = {-6.0, 3.5, -5.0};
        s.camera.wsTarget = {-0.5, 0.5, -0.5};
        s.camera.vfovDeg = 45;
    } else {
        // The lit band under a hovering box is gap (Lx + 1) / (Ly - gap) wide: frame ~40 gaps.
        c.viewWidth = c.gap > 0.0 ? 40.0 * c.gap : 0.05;
        const glm::dvec3 target(snap(-1.0 - 0.25 * c.viewWidth, 30), 0.0, 0.0);
        const double dist = 2.0;
        s.camera.wsTarget = target;
        s.camera.wsEye = snap(target + dist * glm::normalize(glm::dvec3(-0.8, 0.6, -0.2)), 30);
        s.camera.vfovDeg = 2.0 * std::atan(0.5 * c.viewWidth / dist) * 180.0 / std::numbers::pi;
    }
    finalizeScene(s);
    return c;
}

ClosedMeshScene makeClosedMeshScene(bool icosphere, uint64_t seed, int size) {
    ClosedMeshScene c;
    Scene& s = c.scene;
    const glm::dvec3 center(0.25, 2.0, -0.125);
    s.meshes.push_back(makeGrid({0, 0, 0}, {16, 0, 0}, {0, 0, -16}, 8, "floor"));
    MeshPrimitive m = icosphere ? makeIcosphere(center, 1.0, 2, "icosphere")
                                : makeBox(center - 0.75, center + 0.75, "cube");
    rotateMesh(m, randomRotation(seed), center);
    s.meshes.push_back(std::move(m));
    c.wsLight = {1.5, 6.0, 0.75};
    s.lights.push_back(pointLight("key", c.wsLight));
    s.camera.wsEye = {-0.5, 9.0, 4.0};
    s.camera.wsTarget = {-0.5, 0.0, -0.75};
    s.camera.width = s.camera.height = size;
    snapScene(s, 24);
    return c;
}

}  // namespace so::test::hard
