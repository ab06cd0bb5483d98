#include "oracle/area_light.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include <glm/geometric.hpp>

#include "core/error.h"
#include "core/sobol.h"
#include "oracle/lights/area_light_kind.h"
#include "oracle/lights/area_sampling.h"
#include "oracle/offset.h"

namespace so {

AreaLight makeAreaLight(const Light& light, const LocalFrame& frame) {
    AreaLight a;
    a.type = light.type;
    a.kind = &areaLightKind(light.type);
    a.ws = light;
    a.dCenter = frame.lsFromWs(light.wsPosition);
    const double s = frame.lsLength(1.0);  // the frame scales lengths by a power of two
    a.dU = light.wsU * s;
    a.dV = light.wsV * s;
    a.dEmitNormal = light.wsEmitNormal();
    a.dRadius = light.radius * s;
    a.lsCenter = glm::vec3(a.dCenter);
    a.lsU = glm::vec3(a.dU);
    a.lsV = glm::vec3(a.dV);
    a.lsEmitNormal = glm::vec3(a.dEmitNormal);
    a.lsRadius = float(a.dRadius);
    a.kind->init(a, frame);
    // The end margin of the light's farthest point from the frame's origin.
    const double extent = a.kind->extent(a);
    const glm::dvec3 far = glm::abs(a.dCenter) + glm::dvec3(extent);
    a.lsEndMargin = offsetMargin(glm::vec3(far));
    return a;
}

namespace {

// A margin this close to 0 may have either sign by rounding: the float p and n carry ~2^-24 each,
// which moves a margin by up to ~2^-23 (1 + distance); 2^-18 leaves a margin of 32.
constexpr double kTie = 1.0 / 262144.0;

bool isTie(double margin, double distance) {
    return std::fabs(margin) < kTie * (1.0 + distance);
}

// The float decision for one-sided lights: in front of the emitter, light above the horizon, and
// whether either margin is a tie.
struct OneSidedClass {
    bool front = false, above = false;
    bool frontTie = false, aboveTie = false;
};

// Ties decided exactly on the pixel's triangle (exact_facing.h); the cache holds the last
// triangle's answers.
void resolveOneSidedTies(const AreaLight& light, const Accel& accel, const SurfaceBuffer& sb,
                         size_t slot, FacingCache& cache, OneSidedClass& r) {
    if (cache.triangle != sb.originId[slot]) {
        const PixelTriangle t = pixelTriangle(accel, sb, slot);
        cache.triangle = sb.originId[slot];
        cache.emitter = int8_t(emitterSide(t, light.ws));
        cache.above = areaLightAbovePlane(t, light.ws);
    }
    if (r.frontTie && cache.emitter != 0) r.front = cache.emitter > 0;
    if (r.aboveTie) r.above = cache.above;
}

}  // namespace

AreaSkip classifyOneSidedPixel(const AreaLight& light, const glm::dvec3& p, const PixelTies* ties,
                               double top, double reach) {
    const glm::dvec3 c = light.dCenter;
    OneSidedClass r;
    const double front = glm::dot(light.dEmitNormal, p - c);
    r.front = front > 0.0;
    r.frontTie = isTie(front, glm::length(p - c));
    r.above = top > 0.0;
    r.aboveTie = isTie(top, reach);
    if (ties && (r.frontTie || r.aboveTie)) {
        resolveOneSidedTies(light, ties->accel, ties->sb, ties->slot, ties->cache, r);
        ++ties->exactDecisions;
    }
    if (!r.front) return AreaSkip::BehindLight;
    return r.above ? AreaSkip::None : AreaSkip::BelowHorizon;
}

AreaSkip classifyAreaPixel(const AreaLight& light, const glm::dvec3& p, const glm::dvec3& n,
                           const PixelTies* ties) {
    return light.kind->classify(light, p, n, ties);
}

// acos on [-1, 1] by Abramowitz and Stegun 4.4.46 (error below 2e-8 rad, under float's
// resolution), plus a margin that makes it an upper bound: unlike std::acos it vectorises.
float acosUpperBound(float x) {
    const float a = std::fabs(x);
    const float poly =
        1.5707963050f +
        a * (-0.2145988016f +
             a * (0.0889789874f +
                  a * (-0.0501743046f +
                       a * (0.0308918810f +
                            a * (-0.0170881256f + a * (0.0066700901f + a * -0.0012624911f))))));
    const float r = std::sqrt(std::max(0.0f, 1.0f - a)) * poly;
    constexpr float kMargin = 2e-6f;  // the polynomial's error and float rounding, many times over
    return std::min(std::numbers::pi_v<float>,
                    (x < 0.0f ? std::numbers::pi_v<float> - r : r) + kMargin);
}

AreaPixel prepareAreaPixel(const AreaLight& light, const glm::vec3& p, const glm::vec3& n) {
    AreaPixel px;
    px.p = p;
    px.n = n;
    light.kind->preparePixel(light, p, n, px);
    return px;
}

// Directions, segment lengths and weights G / pdf from the points.
SO_SAMPLER_CLONES void finishAreaBatch(const AreaLight& light, const AreaPixel& px,
                                       const LightPoints& q, int count, float margin,
                                       AreaBatch& b) {
    const float* yx = q.x;
    const float* yy = q.y;
    const float* yz = q.z;
    const float* share = q.share;
    for (int k = 0; k < 16; ++k) {
        const float dx = yx[k] - px.p.x, dy = yy[k] - px.p.y, dz = yz[k] - px.p.z;
        const float r2 = dx * dx + dy * dy + dz * dz;
        const float dist = std::sqrt(r2);
        const float inv = 1.0f / dist;
        const float wx = dx * inv, wy = dy * inv, wz = dz * inv;
        const float cosP = px.n.x * wx + px.n.y * wy + px.n.z * wz;
        const float cosY =
            -(light.lsEmitNormal.x * wx + light.lsEmitNormal.y * wy + light.lsEmitNormal.z * wz);
        b.dirX[k] = wx;
        b.dirY[k] = wy;
        b.dirZ[k] = wz;
        b.tfar[k] = std::max(0.0f, dist - margin);
        b.cosine[k] = cosP;
        // Computed for every lane and then selected: a conditional division keeps the loop
        // from vectorising.
        const float g = share[k] * cosP * cosY / r2;
        b.weight[k] = ((k < count) & (cosP > 0.0f) & (cosY > 0.0f)) ? g : 0.0f;
    }
}

SO_SAMPLER_CLONES void fanAreaPoints(const glm::vec3* fan, const float* cdf, int triangles,
                                     const float* su, const float* sv, LightPoints& q) {
    float* yx = q.x;
    float* yy = q.y;
    float* yz = q.z;
    for (int k = 0; k < 16; ++k) {
        // Pick a triangle by area with u, reuse the rest of u inside it (keeps strata).
        int t = 0;
        while (t + 1 < triangles && su[k] >= cdf[t]) ++t;
        const float lo = t ? cdf[t - 1] : 0.0f;
        const float uu = std::min(0.99999994f, (su[k] - lo) / std::max(cdf[t] - lo, 1e-30f));
        const float r = std::sqrt(uu);
        const glm::vec3* tri = fan + 3 * t;
        const glm::vec3 y =
            (1.0f - r) * tri[0] + (r * (1.0f - sv[k])) * tri[1] + (r * sv[k]) * tri[2];
        yx[k] = y.x, yy[k] = y.y, yz[k] = y.z;
    }
}

void mapAreaBatch(const AreaLight& light, const AreaPixel& px, const float* su, const float* sv,
                  int count, AreaBatch& b) {
    light.kind->mapBatch(light, px, su, sv, count, 2.0f * light.lsEndMargin, b);
}

}  // namespace so
