#include "test_scenes.h"
#include "core/lights/make_light.h"

#include <glm/geometric.hpp>

namespace so::test {

MeshPrimitive makeGrid(const glm::dvec3& c, const glm::dvec3& u, const glm::dvec3& v, int n,
                       const std::string& name) {
    MeshPrimitive m;
    m.name = name;
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i)
            m.wsPositions.push_back(c + (double(i) / n - 0.5) * u + (double(j) / n - 0.5) * v);
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            uint32_t a = uint32_t(j * (n + 1) + i), b = a + 1, d = a + uint32_t(n + 1), e = d + 1;
            m.indices.insert(m.indices.end(), {a, b, e, a, e, d});
        }
    return m;
}

MeshPrimitive makeBox(const glm::dvec3& lo, const glm::dvec3& hi, const std::string& name) {
    MeshPrimitive m;
    m.name = name;
    for (int k = 0; k < 8; ++k)
        m.wsPositions.push_back(
            {(k & 1) ? hi.x : lo.x, (k & 2) ? hi.y : lo.y, (k & 4) ? hi.z : lo.z});
    // Two triangles per face, wound counter-clockwise seen from outside.
    const uint32_t faces[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4},
                                  {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
    for (const auto& f : faces)
        m.indices.insert(m.indices.end(), {f[0], f[1], f[2], f[0], f[2], f[3]});
    return m;
}

SquareOccluderScene makeSquareOccluderScene(int width, int height) {
    using S = SquareOccluderScene;
    SquareOccluderScene s;
    Scene& scene = s.scene;
    scene.meshes.push_back(makeGrid({0, 0, 0}, {16, 0, 0}, {0, 0, -16}, 8, "receiver"));
    scene.meshes.push_back(
        makeGrid({0.5 * (S::kX0 + S::kX1), S::kOccluderY, 0.5 * (S::kZ0 + S::kZ1)},
                 {S::kX1 - S::kX0, 0, 0}, {0, 0, -(S::kZ1 - S::kZ0)}, 1, "occluder"));
    scene.camera.wsEye = {0.75, 9.5, 7.25};
    scene.camera.wsTarget = {0.25, 0.0, 0.5};
    scene.camera.vfovDeg = 50.0;
    scene.camera.width = width;
    scene.camera.height = height;
    Light point = pointLight("point", {0.625, 6.0, 0.375});
    Light spot = spotLight("spot", {-0.5, 5.5, 1.25},
                           glm::normalize(glm::dvec3(0.25, -1.0, -0.125)), 40, 30);
    Light sun = directionalLight("sun", glm::normalize(glm::dvec3(0.375, -1.0, 0.25)));
    scene.lights = {point, spot, sun};
    scene.effects = {"hard"};
    finalizeScene(scene);
    return s;
}

Scene transformScene(const Scene& scene, double scale, const glm::dvec3& t) {
    Scene out = scene;
    for (MeshPrimitive& m : out.meshes)
        for (glm::dvec3& p : m.wsPositions) p = p * scale + t;
    out.camera.wsEye = scene.camera.wsEye * scale + t;
    out.camera.wsTarget = scene.camera.wsTarget * scale + t;
    for (Light& l : out.lights) {
        l.wsPosition = l.wsPosition * scale + t;
        l.wsU *= scale;  // area lights' extents (zero for the others)
        l.wsV *= scale;
        l.radius *= scale;
    }
    finalizeScene(out);
    return out;
}

ChannelImage runQuiet(const Scene& scene, int threads) {
    OracleOptions o;
    o.threads = threads;
    return runOracle(scene, o).image;
}

Light makeRectLight(const std::string& name, const glm::dvec3& center, const glm::dvec3& u,
                    const glm::dvec3& v) {
    return rectLight(name, center, u, v);
}

void aimCamera(Scene& scene, const glm::dvec3& eye, const glm::dvec3& target, double vfovDeg,
               int width, int height) {
    scene.camera.wsEye = eye;
    scene.camera.wsTarget = target;
    scene.camera.vfovDeg = vfovDeg;
    scene.camera.width = width;
    scene.camera.height = height;
}

// A long receiver seen from near the ground, a low sun, posts casting long shadows.
Scene makeGroundPostsScene(int width, int height) {
    Scene s;
    s.meshes.push_back(makeGrid({0, 0, -60}, {40, 0, 0}, {0, 0, -128}, 16, "ground"));
    for (int k = 0; k < 12; ++k) {
        const double z = -4.0 - 10.0 * k, x = (k % 3 - 1) * 4.0;
        s.meshes.push_back(makeBox({x - 0.5, 0, z - 0.5}, {x + 0.5, 3, z + 0.5}, "post"));
    }
    s.camera.wsEye = {0.5, 1.5, 2.0};
    s.camera.wsTarget = {0.0, 0.0, -40.0};
    s.camera.vfovDeg = 45.0;
    s.camera.width = width;
    s.camera.height = height;
    s.lights = {directionalLight("sun", glm::normalize(glm::dvec3(0.8, -0.5, 0.3)))};
    s.effects = {"hard"};
    finalizeScene(s);
    return s;
}

PenumbraScene makePenumbraScene(int w, int h) {
    PenumbraScene s;
    Scene& sc = s.scene;
    sc.meshes.push_back(makeGrid({0, 0, 0}, {16, 0, 0}, {0, 0, -16}, 4, "floor"));
    sc.meshes.push_back(makeGrid({0, s.occluder.y, 0}, {2, 0, 0}, {0, 0, -2}, 1, "occluder"));
    // cross(u, v) points down: it lights the floor
    sc.lights = {rectLight(
        "panel", {0.5 * (s.light.x0 + s.light.x1), s.light.y, 0.5 * (s.light.z0 + s.light.z1)},
        {s.light.x1 - s.light.x0, 0, 0}, {0, 0, s.light.z1 - s.light.z0})};
    sc.effects = {"hard", "penumbra"};
    sc.camera.wsEye = {0.25, 6.0, 5.0};
    sc.camera.wsTarget = {0.25, 0.0, 0.0};
    sc.camera.vfovDeg = 36;
    sc.camera.width = w;
    sc.camera.height = h;
    finalizeScene(sc);
    return s;
}

}  // namespace so::test
