// The typed light of the scene model (core/scene.h), which every module reads.
#pragma once

#include <string>
#include <vector>

#include <glm/vec3.hpp>

namespace so {

// The light types: each is a plug-in with one file per layer (core/lights/, oracle/lights/,
// raster_compare/gl/lights/; docs/architecture.md), registered there; the order here is the
// order the scene format lists them in errors. Code outside those folders asks a light's kind
// (core/lights/light_kind.h: isDirectional, hasCone, ...) and makes lights through
// core/lights/make_light.h, rather than naming a value.
enum class LightType { Point, Directional, Spot, Rect, Disk, Sphere, Polygon };
const char* lightTypeName(LightType t);  // the scene format's name
bool isAreaLight(LightType t);           // rect, disk, sphere, polygon

struct Light {
    std::string name;  // unique in the scene, a valid EXR layer name (see channels.h)
    LightType type = LightType::Point;
    glm::dvec3 wsPosition{0.0};              // point, spot
    glm::dvec3 wsDirection{0.0, -1.0, 0.0};  // directional, spot: unit, the way light travels
    double outerConeDeg = 45.0;              // spot: half-angle of the lit cone
    double innerConeDeg = 0.0;               // spot: half-angle of full intensity (raster only)
    // Area lights: wsPosition is the centre.
    glm::dvec3 wsU{0.0}, wsV{0.0};  // rect: full edge vectors; emits on the side of cross(u, v)
    glm::dvec3 wsNormal{0.0};       // disk, polygon: unit, the side it emits on
    double radius = 0.0;            // disk, sphere
    // polygon: 3 to 64, planar, convex, counter-clockwise seen from the side it emits on; its
    // wsPosition is the area centroid (core/lights/polygon.cpp checks all of it).
    std::vector<glm::dvec3> wsVertices{};
    // Rect, disk and polygon emit on one side only: the unit normal of that side (zero for other
    // types).
    glm::dvec3 wsEmitNormal() const;
};

}  // namespace so
