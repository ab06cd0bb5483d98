// Light types as plug-ins, the scene-format layer (pbrt-v4's Light::Create is the model): each type
// is one LightKind in its own file here (point.cpp, spot.cpp, ...) that reads its keys of a scene
// file's light into the typed `Light` (core/scene.h), writes them back, says what the glTF export
// stands in for it, and answers what the other modules ask of a light (isDirectional, hasCone,
// isAreaLight, oneSided) so that none of them names a LightType. Each file registers its kind
// with one line SO_REGISTER_LIGHT_KIND(Class), which core/CMakeLists.txt finds to generate the
// list (cmake/so_registry.cmake), as techniques register; lightKind() and findLightKind() read it.
// The oracle (oracle/lights/) and the raster path (raster_compare/gl/lights/) register their own
// per-type parts the same way. Adding a type: docs/architecture.md, "A light type".
#pragma once

#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "core/json_reader.h"
#include "core/scene.h"

namespace so {

// What `export` writes for a light in KHR_lights_punctual: glTF has no area lights, so an area
// light becomes a spot or point at its centre (docs/export.md).
struct GltfStandIn {
    const char* type = "point";  // "point", "spot" or "directional"
    glm::dvec3 wsAt{0.0};        // the node's translation
    glm::dvec3 wsAlong{0.0};     // the way it shines (spot, directional); zero: no rotation
    double outerConeRad = 0.0, innerConeRad = 0.0;  // spot
};

class LightKind {
  public:
    virtual ~LightKind() = default;
    virtual LightType type() const = 0;
    virtual const char* name() const = 0;  // the scene format's "type"
    virtual bool isArea() const { return false; }
    // Light from a direction (at infinity), not from a point: directional.
    virtual bool isDirectional() const { return false; }
    // Limited to a cone about wsDirection (outerConeDeg): spot.
    virtual bool hasCone() const { return false; }
    // The scene_format this type came with (1: from the start): an older file naming it is an
    // error, and core/scene_writer.h writes no older version for a scene holding it.
    virtual int sceneFormat() const { return 1; }
    // What a light path's keys may set (core/light_path.h): a position (all but directional
    // lights; an area light moves rigidly) and a direction (directional and spot lights).
    virtual bool pathMovesPosition() const { return true; }
    virtual bool pathTurnsDirection() const { return false; }
    // The keys it takes besides "name" and "type" (unknown ones are an error).
    virtual std::vector<std::string> keys() const = 0;
    // Reads j's keys (j is the light object at `field`, e.g. "lights[2]") into `light`, whose name
    // and type are set; a missing or bad value fails through r, naming the field.
    virtual void parse(const json& j, const JsonReader& r, const std::string& field,
                       Light& light) const = 0;
    // Its keys as the scene format spells them, into j (core/scene_writer.h).
    virtual void write(const Light& light, json& j) const = 0;
    // Whether it emits on one side only (rect, disk, polygon): a point behind it is not lit.
    virtual bool oneSided() const { return false; }
    // One-sided emitters: the unit normal of the side it lights; zero for the others.
    virtual glm::dvec3 wsEmitNormal(const Light&) const { return glm::dvec3(0.0); }
    // The glTF export's stand-in and the exact shape for extras.shadow_oracle (core/gltf_export.h).
    virtual GltfStandIn gltfStandIn(const Light& light, const Bounds3d& wsBounds) const = 0;
    virtual void gltfExtras(const Light& light, json& j) const = 0;
    // Area lights: the diameter of the disk with the same area (extras' `size`).
    virtual double equalAreaDiameter(const Light&) const { return 0.0; }

  protected:
    // j[key], or a one-line error naming the field and this type.
    const json& need(const json& j, const JsonReader& r, const std::string& field,
                     const char* key) const;
};

// The stand-in of a one-sided area light: a spot at its centre along its emitting normal whose
// outer half-angle is the narrowest cone that holds every corner of the scene's bounds in front of
// it, between 1 and 85 degrees (a spot's shadow map is a perspective frustum, which cannot reach
// 90).
GltfStandIn spotStandInAlongNormal(const Light& light, const Bounds3d& wsBounds);
// glTF requires innerConeAngle < outerConeAngle; the scene allows them equal.
double innerConeBelowOuter(double innerRad, double outerRad);

// The registered kind of `t`; every LightType has one (checked at the first call).
const LightKind& lightKind(LightType t);
// What modules ask of a light, answered by its kind.
inline bool isDirectional(const Light& l) {
    return lightKind(l.type).isDirectional();
}
inline bool hasCone(const Light& l) {
    return lightKind(l.type).hasCone();
}
inline bool isAreaLight(const Light& l) {
    return lightKind(l.type).isArea();
}
inline bool isOneSided(const Light& l) {
    return lightKind(l.type).oneSided();
}
// Every registered kind, in LightType's order.
const std::vector<const LightKind*>& allLightKinds();
// The type the scene format names `name`, or null.
const LightKind* findLightKind(const std::string& name);
// "point, directional, ...", in the table's order, for error messages.
std::string lightKindNames();

// The registration list: generated (light_list.cpp) from the SO_REGISTER_LIGHT_KIND lines of
// core/lights/*.cpp, and how many there are.
using LightKindList = std::vector<const LightKind*>;
void registerBuiltInLightKinds(LightKindList& registry);
extern const size_t kBuiltInLightKindCount;

// Defines soRegisterLight_<Class> (external linkage: at namespace so's scope, not in an anonymous
// namespace, else the generated list fails to link); the trailing declaration takes the line's
// semicolon. The one instance lives in the function.
#define SO_REGISTER_LIGHT_KIND(Class)                             \
    void soRegisterLight_##Class(::so::LightKindList& registry) { \
        static const Class kind;                                  \
        registry.push_back(&kind);                                \
    }                                                             \
    void soRegisterLight_##Class(::so::LightKindList& registry)

}  // namespace so
