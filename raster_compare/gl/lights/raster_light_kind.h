// Light types as plug-ins, the raster path's layer (core/lights/light_kind.h is the scene
// format's, oracle/lights/area_light_kind.h the oracle's): what the raster path needs to know of a
// light's type. Every type has a RasterLightKind, one file each (point.cpp, directional.cpp,
// spot.cpp, rect.cpp, disk.cpp, sphere.cpp, polygon.cpp), registered with one line
// SO_REGISTER_RASTER_LIGHT_KIND(Class), which raster_compare/gl/CMakeLists.txt finds to generate
// the list (cmake/so_registry.cmake), as techniques register. It says which shadow camera the
// light takes (light_camera.h, which also makes the shaders' LIGHT_* defines from it) and what the
// soft techniques' weight passes integrate over (the EMITTER_* defines), its shape (issue 62: the
// techniques ask it, never guess it from which of Light's fields are set) and its points as a
// receiver samples them (shadow rays); an area light's kind adds its width (PCSS-like techniques)
// and its sample points (the soft techniques). Every area light's shadow camera is the cube from
// its centre and its facing the one-sided or sphere emitter's (light_facing.h), so those need
// nothing per type.
#pragma once

#include <vector>

#include <glm/vec3.hpp>

#include "core/scene.h"
#include "raster_compare/gl/shadow_maps/light_camera.h"

namespace so {

class RasterAreaLightKind;

// What a light is as the raster path's techniques sample it (smrt's rays, the shadow rays): the
// kind's answer, world space. A new shape is a value here, and the switches on it (smrt.cpp) fail
// to compile (-Wswitch) until they say how they take it.
struct RasterLightShape {
    enum class Kind {
        Point,      // one point, wsCentre (point and spot lights)
        Direction,  // a direction, Light::wsDirection (directional lights)
        Rect,       // the parallelogram wsCentre + s wsU + t wsV, s and t in [-1/2, 1/2]
        Disk,       // the ellipse wsCentre + x wsU + y wsV, x^2 + y^2 <= 1 (a disk: equal axes)
        Sphere,     // the sphere of `radius` about wsCentre
        Polygon,    // the planar polygon Light::wsVertices
    };
    Kind kind = Kind::Point;
    glm::dvec3 wsCentre{0.0};
    glm::dvec3 wsU{0.0}, wsV{0.0};  // Rect: its full edges; Disk: its perpendicular semi-axes
    double radius = 0.0;            // Sphere
};

// A point on a light and the emitter's normal there (zero for a point or a direction), world
// space.
struct LightPoint {
    glm::dvec3 wsPoint{0.0}, wsNormal{0.0};
};

class RasterLightKind {
  public:
    virtual ~RasterLightKind() = default;
    virtual LightType type() const = 0;
    // Its own shadow camera (fitLightCamera): Ortho (directional), Perspective (spot), or the
    // cube from its position (point lights, area lights from their centre).
    virtual LightCamera::Kind cameraKind() const { return LightCamera::Kind::Cube; }
    // What a weight pass integrates over (accumulate.glsl): "#define EMITTER_POINT\n" (one
    // sample, a punctual light), EMITTER_ONE_SIDED (a one-sided area light's samples),
    // EMITTER_SPHERE.
    virtual const char* emitterDefine() const { return "#define EMITTER_POINT\n"; }
    // Area lights: their part; null for punctual lights.
    virtual const RasterAreaLightKind* area() const { return nullptr; }
    // Its shape: every kind answers, from the fields its own type reads.
    virtual RasterLightShape shape(const Light& light) const = 0;
    // The point for (u, v) in [0, 1)^2 as a receiver at wsFrom samples the light, and the
    // emitter's normal there: a punctual light's one point (normal zero; a directional light's
    // rays take its direction instead); an area light's samplePoint (uniform by area) with its
    // emitting normal; a sphere's visible cap (sphere.cpp).
    virtual LightPoint pointSeenFrom(const Light& light, const glm::dvec3& wsFrom, double u,
                                     double v) const;
};

class RasterAreaLightKind : public RasterLightKind {
  public:
    const char* emitterDefine() const override { return "#define EMITTER_ONE_SIDED\n"; }
    const RasterAreaLightKind* area() const override { return this; }
    // The side of the square with the light's area seen face-on (sphere: of its silhouette disk):
    // the one size PCSS-like techniques take (light_camera.h, lightWidth).
    virtual double width(const Light& light) const = 0;
    // The point for (u, v) in [0, 1)^2, uniform by area over the light (sphere: the whole sphere),
    // world space: the soft techniques' light samples (light_samples.h).
    virtual glm::dvec3 samplePoint(const Light& light, double u, double v) const = 0;
    LightPoint pointSeenFrom(const Light& light, const glm::dvec3& wsFrom, double u,
                             double v) const override;
};

// The registered kind of a light type; every type has one (checked at the first call).
const RasterLightKind& rasterLightKind(LightType type);
// Its area part; null for punctual lights.
inline const RasterAreaLightKind* rasterAreaLightKind(LightType type) {
    return rasterLightKind(type).area();
}

// The registration list: generated (raster_light_list.cpp) from the SO_REGISTER_RASTER_LIGHT_KIND
// lines of raster_compare/gl/lights/*.cpp, and how many there are.
using RasterLightKindList = std::vector<const RasterLightKind*>;
void registerBuiltInRasterLightKinds(RasterLightKindList& registry);
extern const size_t kBuiltInRasterLightKindCount;

// Defines soRegisterRasterLight_<Class> at namespace so's scope (as SO_REGISTER_LIGHT_KIND does).
#define SO_REGISTER_RASTER_LIGHT_KIND(Class)                                  \
    void soRegisterRasterLight_##Class(::so::RasterLightKindList& registry) { \
        static const Class kind;                                              \
        registry.push_back(&kind);                                            \
    }                                                                         \
    void soRegisterRasterLight_##Class(::so::RasterLightKindList& registry)

}  // namespace so
