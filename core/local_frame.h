// The frame both paths work in: world space recentred on the geometry's bounds and scaled by a
// power of two, computed in double before anything becomes float. Because the offset and the scale
// are exact, a scene translated by a dyadic amount or scaled by 2^k reaches Embree as the very same
// floats, so the ground truth does not depend on where the scene sits in the world.
#pragma once

#include <algorithm>
#include <cmath>

#include <glm/vec3.hpp>

#include "core/scene.h"

namespace so {

struct LocalFrame {
    glm::dvec3 wsCenter{0.0};
    int exponent = 0;  // lsPoint = (wsPoint - wsCenter) * 2^-exponent

    static LocalFrame fit(const Bounds3d& wsBounds) {
        LocalFrame f;
        if (wsBounds.empty()) return f;
        f.wsCenter = wsBounds.center();
        glm::dvec3 half = 0.5 * wsBounds.diagonal();
        double m = std::max({half.x, half.y, half.z});
        if (m > 0.0) std::frexp(m, &f.exponent);  // m = mant * 2^e, mant in [0.5, 1)
        return f;
    }
    glm::dvec3 lsFromWs(const glm::dvec3& ws) const {
        glm::dvec3 d = ws - wsCenter;
        return {std::ldexp(d.x, -exponent), std::ldexp(d.y, -exponent), std::ldexp(d.z, -exponent)};
    }
    glm::dvec3 wsFromLs(const glm::dvec3& ls) const {
        return glm::dvec3(std::ldexp(ls.x, exponent), std::ldexp(ls.y, exponent),
                          std::ldexp(ls.z, exponent)) +
               wsCenter;
    }
    double wsLength(double lsLength) const { return std::ldexp(lsLength, exponent); }
    double lsLength(double wsLength) const { return std::ldexp(wsLength, -exponent); }
};

}  // namespace so
