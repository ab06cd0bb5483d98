#include "oracle/exact_facing.h"

#include <utility>

#include <glm/geometric.hpp>

#include "core/error.h"
#include "oracle/exact_sign.h"
#include "oracle/lights/area_light_kind.h"

namespace so {

PixelTriangle pixelTriangle(const Accel& accel, const SurfaceBuffer& sb, size_t slot) {
    SO_CHECK(sb.hit[slot]);
    PixelTriangle t;
    accel.wsTriangle(sb.meshId[slot], sb.primId[slot], t.a, t.b, t.c);
    // The pixel's normal is the local-frame triangle's, flipped towards the camera; the frame
    // translates and scales by a positive power of two, so its cross product points the same
    // way, and the dot product is +-|cross| (never near zero: the triangle has an area).
    glm::dvec3 la, lb, lc;
    accel.triangle(sb.meshId[slot], sb.primId[slot], la, lb, lc);
    if (glm::dot(glm::cross(lb - la, lc - la), glm::dvec3(sb.lsNormal(slot))) < 0.0)
        std::swap(t.b, t.c);
    return t;
}

int facingPoint(const PixelTriangle& t, const glm::dvec3& wsLight) {
    return exact::orient(t.a, t.b, t.c, wsLight);
}

int facingDirection(const PixelTriangle& t, const glm::dvec3& wsToLight) {
    return exact::orientDirection(t.a, t.b, t.c, wsToLight);
}

int emitterSide(const PixelTriangle& t, const Light& light) {
    const AreaLightKind& kind = areaLightKind(light.type);
    int front = 0;
    for (const glm::dvec3& v : {t.a, t.b, t.c}) front += kind.sideOfPlane(light, v) > 0;
    return front == 3 ? 1 : front == 0 ? -1 : 0;
}

bool areaLightAbovePlane(const PixelTriangle& t, const Light& light) {
    return areaLightKind(light.type).abovePlane(t, light);
}

}  // namespace so
