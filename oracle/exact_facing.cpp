#include "oracle/exact_facing.h"

#include <utility>

#include <glm/geometric.hpp>

#include "core/error.h"
#include "oracle/exact_sign.h"

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
    SO_CHECK(light.type == LightType::Rect || light.type == LightType::Disk ||
             light.type == LightType::Polygon);
    int front = 0;
    for (const glm::dvec3& v : {t.a, t.b, t.c}) {
        // A rect's plane is the span of its edges (its unit normal is rounded; the span is not).
        // A polygon's is the plane through its first vertex with its (rounded) normal, as a disk's.
        const int s = light.type == LightType::Rect
                          ? exact::sideOfSpan(light.wsPosition, light.wsU, light.wsV, v)
                      : light.type == LightType::Polygon
                          ? exact::sideOfPlane(light.wsVertices[0], light.wsNormal, v)
                          : exact::sideOfPlane(light.wsPosition, light.wsNormal, v);
        front += s > 0;
    }
    return front == 3 ? 1 : front == 0 ? -1 : 0;
}

bool areaLightAbovePlane(const PixelTriangle& t, const Light& light) {
    if (light.type == LightType::Disk)
        return exact::diskAbovePlane(t.a, t.b, t.c, light.wsPosition, light.wsNormal, light.radius);
    if (light.type == LightType::Polygon) {
        for (const glm::dvec3& v : light.wsVertices)
            if (exact::orient(t.a, t.b, t.c, v) > 0) return true;
        return false;
    }
    SO_CHECK(light.type == LightType::Rect);
    // Corners centre +- u/2 +- v/2: halving a double is exact, the sum is taken exactly.
    for (int k = 0; k < 4; ++k) {
        const glm::dvec3 hu = ((k & 1) ? 0.5 : -0.5) * light.wsU;
        const glm::dvec3 hv = ((k & 2) ? 0.5 : -0.5) * light.wsV;
        if (exact::orient(t.a, t.b, t.c, light.wsPosition, hu, hv) > 0) return true;
    }
    return false;
}

}  // namespace so
