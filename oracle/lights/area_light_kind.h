// Area light types as plug-ins, the oracle's layer (core/lights/light_kind.h is the scene
// format's): one AreaLightKind per type in its own file here (rect.cpp, disk.cpp, sphere.cpp,
// polygon.cpp) holds everything the oracle does differently by type: the light's local-frame data,
// which pixels it cannot reach, the per-pixel set-up and the 16-sample batches of the sampled pass
// (area_light.h), the points the near-field test needs (near_field.h), and the exact pass's answer
// at a point (exact_penumbra.h), the exact side and horizon decisions on a pixel's triangle
// (exact_facing.h), and the verifier's parts (its independent samples, reference_light.h; the disk
// it bounds V over, verify.cpp). Each file registers its kind with one line
// SO_REGISTER_AREA_LIGHT_KIND(Class), which oracle/CMakeLists.txt finds to generate the list
// (cmake/so_registry.cmake); areaLightKind() reads it. Adding a type is a file here.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include <glm/vec3.hpp>

#include "core/local_frame.h"
#include "core/scene.h"
#include "oracle/polygon_visibility.h"

namespace so {

struct AreaLight;
struct AreaPixel;
struct AreaBatch;
struct PixelTies;
struct NearTarget;
struct ExactPenumbraOptions;
struct DiskExactVisibility;
struct DiskBoundOptions;
struct DiskLightShape;
struct PixelTriangle;
class ReferenceSampler;
enum class AreaSkip : uint8_t;

// The exact pass's answer at one point: V with its counts, and for a bounded light (disk,
// sphere) the stated error (disk_exact.h), the gathering polygon's sides where the shadows were
// clipped against it (0 where a shortcut answered) and whether the error is within
// --bound-target.
struct ExactLightAnswer {
    PolygonVisibility result;
    double halfWidth = 0.0;
    uint32_t sides = 0;
    bool reachedTarget = true;
};

// A disk's exact V as an answer (disk.cpp; the sphere's is its silhouette disk's).
ExactLightAnswer diskAnswer(const DiskExactVisibility& d, const DiskBoundOptions& options);

class AreaLightKind {
  public:
    virtual ~AreaLightKind() = default;
    virtual LightType type() const = 0;
    // makeAreaLight's part for this type, after the common fields (centre, edges, normal, radius
    // in the local frame) are set; and how far the light's points lie from its centre.
    virtual void init(AreaLight&, const LocalFrame&) const {}
    virtual double extent(const AreaLight& light) const = 0;
    // classifyAreaPixel (area_light.h).
    virtual AreaSkip classify(const AreaLight& light, const glm::dvec3& p, const glm::dvec3& n,
                              const PixelTies* ties) const = 0;
    // prepareAreaPixel's part for this type (px.p and px.n are set).
    virtual void preparePixel(const AreaLight&, const glm::vec3&, const glm::vec3&,
                              AreaPixel&) const {}
    // mapAreaBatch; `margin`: how far short of the light each segment stops.
    virtual void mapBatch(const AreaLight& light, const AreaPixel& px, const float* su,
                          const float* sv, int count, float margin, AreaBatch& b) const = 0;
    // Points whose convex hull holds the light (near_field.h).
    virtual NearTarget nearTarget(const AreaLight& light) const = 0;
    // How the sampled pass picks its points, as oracle.json says.
    virtual const char* sampling() const { return "uniform by area"; }
    // Whether the exact pass bounds V (disk, sphere: an interval, the `bound` channel) rather
    // than giving it exactly (rect, polygon).
    virtual bool bounded() const { return false; }
    virtual ExactLightAnswer exactAt(const ExactTracer& tracer, const AreaLight& light,
                                     const ExactPenumbraOptions& options,
                                     const OccluderOptions& more, const glm::dvec3& p,
                                     const glm::dvec3& n, TriangleId self) const = 0;
    // One-sided types: the exact side of the light's plane a world-space point lies on (1: the
    // side it emits on, -1: behind it, 0: in it), for exact_facing.h's emitterSide.
    virtual int sideOfPlane(const Light& light, const glm::dvec3& wsPoint) const;
    // One-sided types: whether some point of the light lies strictly above t's plane, exactly
    // (exact_facing.h, areaLightAbovePlane).
    virtual bool abovePlane(const PixelTriangle& t, const Light& light) const;
    // The verifier's independent samples of the light, uniform by area (reference_light.h).
    virtual std::shared_ptr<const ReferenceSampler> reference(const Light& light,
                                                              const LocalFrame& frame) const = 0;
    // Bounded types: the disk whose V the exact pass bounds as seen from p (local frame), as the
    // verifier re-runs it; false where no point of the light is seen (inside a sphere).
    virtual bool boundedDisk(const Light& light, const LocalFrame& frame, const glm::dvec3& p,
                             DiskLightShape& disk) const;
};

// The registered kind of an area light type (rect, disk, sphere, polygon); an InternalError for
// a punctual type.
const AreaLightKind& areaLightKind(LightType type);

// The registration list: generated (area_light_list.cpp) from the SO_REGISTER_AREA_LIGHT_KIND
// lines of oracle/lights/*.cpp, and how many there are.
using AreaLightKindList = std::vector<const AreaLightKind*>;
void registerBuiltInAreaLightKinds(AreaLightKindList& registry);
extern const size_t kBuiltInAreaLightKindCount;

// Defines soRegisterAreaLight_<Class> at namespace so's scope (as SO_REGISTER_LIGHT_KIND does).
#define SO_REGISTER_AREA_LIGHT_KIND(Class)                                \
    void soRegisterAreaLight_##Class(::so::AreaLightKindList& registry) { \
        static const Class kind;                                          \
        registry.push_back(&kind);                                        \
    }                                                                     \
    void soRegisterAreaLight_##Class(::so::AreaLightKindList& registry)

}  // namespace so
