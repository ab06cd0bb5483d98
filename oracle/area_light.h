// Area lights in the local frame, and how the oracle samples them (docs/oracle.md).
//
// The shadow factor is V(p) = integral_L v G dA / integral_L G dA with G = cos_p cos_y / r^2
// (one-sided cos_y for rect and disk). Samples y_i with pdf p_i give weights w_i = G_i / p_i and
// the ratio estimator V = sum w_i v_i / sum w_i, which is exactly 1 where nothing blocks.
//   rect, disk: uniform by area (disk: concentric map), w = max(cos_p,0) max(cos_y,0) / r^2;
//               a rect partly below the receiver's horizon is clipped to it first
//   polygon:    uniform by area over its fan of triangles from vertex 0 (a triangle picked by its
//               area share, then uniform in it), w as for rect, not clipped to the horizon (a
//               sample below it has weight 0)
//   sphere:     in the solid angle of the visible cap only: the cone towards the sphere in rings of
//               1 - cos(theta), and where the horizon cuts the cone, only the rings with a part
//               above it, picked in proportion to (a bound of) that part, and the angle around
//               each ring over its part above the horizon; w = max(cos_p, 0) times the ring's
//               visible share over the bound its bin was picked by
// (constant factors common to all samples of a pixel are dropped: they cancel in the ratio).
#pragma once

#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "core/local_frame.h"
#include "core/scene.h"
#include "oracle/accel.h"
#include "oracle/exact_facing.h"
#include "oracle/surface_buffer.h"

namespace so {

class AreaLightKind;

struct AreaLight {
    LightType type{};                     // ws.type, set by makeAreaLight
    const AreaLightKind* kind = nullptr;  // its type's oracle part (oracle/lights/)
    glm::vec3 lsCenter{0.0f};
    glm::vec3 lsU{0.0f}, lsV{0.0f};    // rect: full edges
    glm::vec3 lsEmitNormal{0.0f};      // rect, disk: unit
    glm::vec3 lsE1{0.0f}, lsE2{0.0f};  // disk: unit axes in its plane
    float lsRadius = 0.0f;             // disk, sphere
    float lsEndMargin = 0.0f;          // shadow rays stop this far short of the light
    // Rect corners / disk extents, for the horizon test, in double.
    glm::dvec3 dCenter{0.0}, dU{0.0}, dV{0.0}, dEmitNormal{0.0};
    double dRadius = 0.0;
    // polygon: its vertices; its fan from vertex 0 (3 float points a triangle) with the triangles'
    // cumulative area shares; the rectangle in its plane that holds it (corner + s u + t v, s and
    // t in [0, 1], u and v orthogonal along its first edge), the exact pass's frame.
    std::vector<glm::dvec3> dVertices;
    std::vector<glm::vec3> lsFan;
    std::vector<float> fanCdf;
    glm::dvec3 dBoxCorner{0.0}, dBoxU{0.0}, dBoxV{0.0};
    Light ws;  // the scene's light, for the exact decisions
};
AreaLight makeAreaLight(const Light& light, const LocalFrame& frame);

enum class AreaSkip : uint8_t { None, BelowHorizon, BehindLight, InsideLight };

// What one pixel needs to sample the light: computed once per pixel.
struct AreaPixel {
    glm::vec3 p{0.0f}, n{0.0f};
    // sphere: cone towards the centre, t1 towards the receiver's normal (so the horizon cuts each
    // ring of the cone symmetrically about t1); horizonC = n.wc, horizonS = n.t1 >= 0
    glm::vec3 wc{0.0f}, t1{0.0f}, t2{0.0f};
    float dist = 0.0f, oneMinusCosMax = 0.0f, radius2 = 0.0f;
    float horizonC = 1.0f, horizonS = 0.0f;
    // sphere cut by the horizon: rings y = 1 - cos(theta) in [sphereYLo, oneMinusCosMax] (below
    // sphereYLo every ring lies under the horizon), in kSphereBins bins of equal width picked by
    // sphereCdf; sphereBinArc bounds each bin's visible half-angle from above.
    static constexpr int kSphereBins = 16;
    bool sphereClipped = false;
    float sphereYLo = 0.0f, sphereBinY = 0.0f;
    float sphereCdf[kSphereBins] = {};
    float sphereBinArc[kSphereBins] = {};
    // disk partly below the horizon: points c + r (cos t a + sin t a_perp) are above it where
    // diskH + r diskS cos t > 0 (a: the normal's direction within the disk's plane, in (e1, e2))
    bool diskClipped = false;
    float diskH = 0.0f, diskS = 0.0f, diskA1 = 1.0f, diskA2 = 0.0f;
    // rect partly below the horizon: the part above it, as a fan of up to 3 triangles sampled by
    // area, so that no sample is spent where G = 0 (grazing receivers would otherwise get none).
    int clippedTriangles = 0;
    glm::vec3 tri[3][3];
    float triCdf[3] = {0, 0, 0};
};

// What the exact decisions need to know about the pixel, and a per-thread cache (exact_facing.h).
struct PixelTies {
    const Accel& accel;
    const SurfaceBuffer& sb;
    size_t slot;
    FacingCache& cache;
    uint64_t& exactDecisions;  // incremented where a tie was decided exactly
};

// Whether the pixel at p (unit normal n) can receive light at all: the light entirely below the
// horizon, p behind a one-sided emitter, or p inside a sphere light get V = 0 without rays. With
// `ties`, a decision whose float margin is within its rounding error of 0 is made exactly on the
// pixel's triangle (the light in the receiver's plane, the receiver in the emitter's plane).
AreaSkip classifyAreaPixel(const AreaLight& light, const glm::dvec3& p, const glm::dvec3& n,
                           const PixelTies* ties);
AreaPixel prepareAreaPixel(const AreaLight& light, const glm::vec3& p, const glm::vec3& n);

// Up to 16 samples: unit directions from p, segment lengths (tfar) and weights; weight 0 means
// "no ray" (below the horizon or behind the emitter).
struct AreaBatch {
    alignas(64) float dirX[16];
    alignas(64) float dirY[16];
    alignas(64) float dirZ[16];
    alignas(64) float tfar[16];
    alignas(64) float weight[16];
    alignas(64) float cosine[16];  // to the receiver's normal (tangency: accel.h)
};
// acos(x) for x in [-1, 1], never below the true value and within 3e-6 of it (branch-free, so the
// samplers' loops vectorise; exposed for tests).
float acosUpperBound(float x);

// From 16 given points of the unit square (lanes >= count get weight 0).
void mapAreaBatch(const AreaLight& light, const AreaPixel& px, const float* su, const float* sv,
                  int count, AreaBatch& b);

}  // namespace so
