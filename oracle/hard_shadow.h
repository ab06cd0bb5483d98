// Exact hard shadows for point, spot and directional lights: one shadow ray per pixel that can see
// the light, traced as coherent 16-ray packets over 4x4 pixel tiles.
//
// Per pixel (docs/oracle.md):
//   background (no primary hit)        V = 0, cos = 0, no ray
//   cos <= 0 (light behind the normal) V = 0, no ray   ("attached" shadow)
//     (decided exactly on the scene's doubles where the float cosine is within its rounding
//     error of 0, and so is the side of a one-sided emitter: exact_facing.h)
//   spot, outside the outer cone       V = 0, no ray   ("outside_cone")
//   rect/disk at its centre, behind it V = 0, no ray   ("behind_light")
//   otherwise                          V = 1 if the segment from the offset origin to the light
//                                      (stopping the offset margin short of it; directional: to
//                                      infinity) is unoccluded, else 0.
#pragma once

#include <cstdint>

#include <glm/vec3.hpp>

#include "core/scene.h"
#include "oracle/accel.h"
#include "oracle/exact_facing.h"
#include "oracle/pass_stats.h"
#include "oracle/surface_buffer.h"

namespace so {

class Progress;

// A punctual light in the local frame.
struct HardLight {
    // What the loops branch on, asked of the light's kind once (core/lights/light_kind.h): a
    // directional light's rays go along -lsDirection without end; a spot's stop at its cone.
    // Neither: a point light, or an area light traced at its centre.
    bool directional = false;
    bool spot = false;
    glm::dvec3 lsPosition{0.0};
    glm::dvec3 lsDirection{0.0, -1.0, 0.0};  // the way light travels, unit
    double cosOuter = -1.0;                  // spot: cos of the outer half-angle
    float lsEndMargin = 0.0f;                // the segment stops this far short of the light
    glm::vec3 lsPositionF{0.0f}, lsDirectionF{0.0f, -1.0f, 0.0f};  // the same, as the rays use them
    float cosOuterF = -1.0f;
    bool oneSided = false;          // a rect or disk light traced at its centre
    glm::vec3 lsEmitNormalF{0.0f};  // its emitting side
    float lsTieScale = 0.0f;        // the light position's part of the tie bound (hard_shadow.cpp)
    Light ws;                       // the scene's light, for the exact decisions
};
HardLight makeHardLight(const Light& light, const LocalFrame& frame);

// Padding: a lane of an edge tile that lies outside the image (never reported).
enum class ShadowRayKind : uint8_t {
    Background,
    Attached,
    OutsideCone,
    BehindLight,
    Traced,
    Padding,
    Count
};

// One pixel's shadow ray: its kind, the cosine to the light, and for Traced the ray itself
// (direction unit, tnear = 0). Shared by the oracle and the benchmark's plain Embree loops so both
// trace exactly the same rays.
struct ShadowRaySetup {
    ShadowRayKind kind = ShadowRayKind::Background;
    double cosine = 0.0;
    glm::vec3 org{0.0f}, dir{0.0f};
    float tfar = 0.0f;
};
// The 16 lanes of one tile (slots base .. base + 15) at once; setupShadowRay is one lane of it.
struct PacketSetup {
    alignas(64) float cosine[16];
    alignas(64) float dirX[16];
    alignas(64) float dirY[16];
    alignas(64) float dirZ[16];
    alignas(64) float tfar[16];
    ShadowRayKind kind[16];
    // Kept from packet to packet of one thread and light: the last exact decision, and how many
    // lanes were decided exactly.
    FacingCache facingCache;
    uint64_t exactDecisions = 0;
};
void setupPacket(const Accel& accel, const SurfaceBuffer& sb, size_t base, const HardLight& light,
                 PacketSetup& ps);

// `slot` indexes the tile-major surface buffer (SurfaceBuffer::slot).
ShadowRaySetup setupShadowRay(const Accel& accel, const SurfaceBuffer& sb, size_t slot,
                              const HardLight& light);

// Where the pass writes, one float per pixel of the surface buffer's image (or band) each.
struct HardShadowPlanes {
    float* V = nullptr;
    float* cosine = nullptr;
    // With the contact effect: the distance to the first occluder in world units (+inf where
    // unoccluded, -1 where no ray was traced); the rays are then closest-hit queries. Null: cheaper
    // any-hit queries.
    float* occDist = nullptr;
};

// Fills the planes. Runs in parallel inside the caller's task arena.
HardShadowStats traceHardShadows(const Accel& accel, const SurfaceBuffer& sb,
                                 const HardLight& light, const HardShadowPlanes& out,
                                 Progress* progress);

}  // namespace so
