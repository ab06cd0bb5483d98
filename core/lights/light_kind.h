// Light types as plug-ins, the scene-format layer (pbrt-v4's Light::Create is the model): each type
// is one LightKind in its own file here (point.cpp, spot.cpp, ...) that reads its keys of a scene
// file's light into the typed `Light` (core/scene.h), writes them back, and says what the glTF
// export stands in for it. lightKind() and findLightKind() are the one table of types
// (light_kind.cpp); the oracle (oracle/lights/) and the raster path keep their own per-type parts.
// Adding a type: a LightType value, a file here, one line in the table (docs/architecture.md).
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

// The registered type of `t`; every LightType has one.
const LightKind& lightKind(LightType t);
// The type the scene format names `name`, or null.
const LightKind* findLightKind(const std::string& name);
// "point, directional, ...", in the table's order, for error messages.
std::string lightKindNames();

// Each type's one instance (defined in its own file), for the table.
const LightKind& pointLightKind();
const LightKind& directionalLightKind();
const LightKind& spotLightKind();
const LightKind& rectLightKind();
const LightKind& diskLightKind();
const LightKind& sphereLightKind();
const LightKind& polygonLightKind();

}  // namespace so
