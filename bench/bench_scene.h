// The generated benchmark scene: a bumpy terrain grid of 2 * grid^2 triangles and 16 floating
// spheres (167,936 triangles at grid = 256), seen from above at size x size pixels. No lights.
#pragma once

#include <cmath>

#include <glm/geometric.hpp>

#include "core/scene.h"

namespace so::bench {

inline MeshPrimitive terrain(int n) {
    MeshPrimitive m;
    m.name = "terrain";
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) {
            double x = -20.0 + 40.0 * i / n, z = 20.0 - 40.0 * j / n;
            double y =
                0.8 * std::sin(0.4 * x) * std::cos(0.33 * z) + 0.25 * std::sin(1.7 * x + 0.9 * z);
            m.wsPositions.push_back({x, y, z});
        }
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            uint32_t a = uint32_t(j * (n + 1) + i), b = a + 1, d = a + uint32_t(n + 1), e = d + 1;
            m.indices.insert(m.indices.end(), {a, d, e, a, e, b});
        }
    return m;
}

inline MeshPrimitive sphere(const glm::dvec3& c, double r, int n, int mrings) {
    MeshPrimitive m;
    m.name = "sphere";
    for (int j = 0; j <= mrings; ++j)
        for (int i = 0; i <= n; ++i) {
            double th = M_PI * j / mrings, ph = 2 * M_PI * i / n;
            m.wsPositions.push_back(c + r * glm::dvec3(std::sin(th) * std::cos(ph), std::cos(th),
                                                       std::sin(th) * std::sin(ph)));
        }
    for (int j = 0; j < mrings; ++j)
        for (int i = 0; i < n; ++i) {
            uint32_t a = uint32_t(j * (n + 1) + i), b = a + 1, d = a + uint32_t(n + 1), e = d + 1;
            m.indices.insert(m.indices.end(), {a, b, e, a, e, d});
        }
    return m;
}

inline Scene makeBenchScene(int grid, int size) {
    Scene scene;
    scene.meshes.push_back(terrain(grid));
    for (int k = 0; k < 16; ++k) {
        double a = 2 * M_PI * k / 16;
        scene.meshes.push_back(
            sphere({9 * std::cos(a), 3.0 + (k % 3), 9 * std::sin(a)}, 1.2, 48, 24));
    }
    scene.camera.wsEye = {0, 22, 26};
    scene.camera.wsTarget = {0, 0, 0};
    scene.camera.vfovDeg = 55;
    scene.camera.width = scene.camera.height = size;
    finalizeScene(scene);
    return scene;
}

}  // namespace so::bench
