#include "oracle/area_light.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include <glm/geometric.hpp>

#include "core/error.h"
#include "core/sobol.h"
#include "oracle/offset.h"

namespace so {

// The samplers' loops, once for AVX2 (eight lanes at a time) and once for any x86-64, chosen at
// run time. Neither enables fused multiply-add, and both round every operation the same IEEE way,
// so the samples are the same bits on any CPU.
#define SO_SAMPLER_CLONES __attribute__((target_clones("avx2", "default")))

AreaLight makeAreaLight(const Light& light, const LocalFrame& frame) {
    AreaLight a;
    a.type = light.type;
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
    if (light.type == LightType::Disk) {
        glm::dvec3 m = a.dEmitNormal;
        glm::dvec3 helper = std::fabs(m.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
        glm::dvec3 e1 = glm::normalize(glm::cross(helper, m));
        a.lsE1 = glm::vec3(e1);
        a.lsE2 = glm::vec3(glm::cross(m, e1));
    }
    // The end margin of the light's farthest point from the frame's origin.
    const double extent =
        light.type == LightType::Rect ? 0.5 * (glm::length(a.dU) + glm::length(a.dV)) : a.dRadius;
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

// The float decision for rect and disk lights: in front of the emitter, light above the horizon,
// and whether either margin is a tie.
struct OneSidedClass {
    bool front = false, above = false;
    bool frontTie = false, aboveTie = false;
};

OneSidedClass classifyOneSided(const AreaLight& light, const glm::dvec3& p, const glm::dvec3& n) {
    const glm::dvec3 c = light.dCenter;
    OneSidedClass r;
    const double front = glm::dot(light.dEmitNormal, p - c);
    r.front = front > 0.0;
    r.frontTie = isTie(front, glm::length(p - c));
    if (light.type == LightType::Rect) {
        double top = -std::numeric_limits<double>::infinity(), reach = 0.0;
        for (int k = 0; k < 4; ++k) {
            glm::dvec3 corner =
                c + ((k & 1) ? 0.5 : -0.5) * light.dU + ((k & 2) ? 0.5 : -0.5) * light.dV;
            top = std::max(top, glm::dot(n, corner - p));
            reach = std::max(reach, glm::length(corner - p));
        }
        r.above = top > 0.0;
        r.aboveTie = isTie(top, reach);
    } else {
        // The disk's highest point above p's tangent plane.
        const double nm = glm::dot(n, light.dEmitNormal);
        const double top =
            glm::dot(n, c - p) + light.dRadius * std::sqrt(std::max(0.0, 1.0 - nm * nm));
        r.above = top > 0.0;
        r.aboveTie = isTie(top, glm::length(c - p) + light.dRadius);
    }
    return r;
}

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

AreaSkip classifyAreaPixel(const AreaLight& light, const glm::dvec3& p, const glm::dvec3& n,
                           const PixelTies* ties) {
    switch (light.type) {
        case LightType::Rect:
        case LightType::Disk: {
            OneSidedClass r = classifyOneSided(light, p, n);
            if (ties && (r.frontTie || r.aboveTie)) {
                resolveOneSidedTies(light, ties->accel, ties->sb, ties->slot, ties->cache, r);
                ++ties->exactDecisions;
            }
            if (!r.front) return AreaSkip::BehindLight;
            return r.above ? AreaSkip::None : AreaSkip::BelowHorizon;
        }
        case LightType::Sphere: {
            // A sphere has no plane to lie in: its centre in the receiver's plane is above it by
            // the radius.
            const glm::dvec3 d = light.dCenter - p;
            if (glm::dot(d, d) <= light.dRadius * light.dRadius) return AreaSkip::InsideLight;
            return glm::dot(n, d) + light.dRadius > 0.0 ? AreaSkip::None : AreaSkip::BelowHorizon;
        }
        default:
            return AreaSkip::None;
    }
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

namespace {

// sin and cos on [-pi/4, pi/4] by their Taylor polynomials (errors below 1e-8, under float's
// resolution): unlike std::sin/cos these vectorise, and the samplers call them for every sample.
inline void sincosQuarterPi(float x, float& s, float& c) {
    const float x2 = x * x;
    s = x *
        (1.0f + x2 * (-1.0f / 6 + x2 * (1.0f / 120 + x2 * (-1.0f / 5040 + x2 * (1.0f / 362880)))));
    c = 1.0f + x2 * (-0.5f + x2 * (1.0f / 24 + x2 * (-1.0f / 720 + x2 * (1.0f / 40320))));
}

// sin and cos of 2 pi v for v in [0, 1): reduced to a quarter turn around pi/4 + q pi/2.
inline void sincos2Pi(float v, float& s, float& c) {
    const float q = float(int(v * 4.0f));  // v >= 0: truncation is floor, and vectorises
    const float x =
        2.0f * std::numbers::pi_v<float> * (v - 0.25f * q) - std::numbers::pi_v<float> / 4;
    float sx, cx;
    sincosQuarterPi(x, sx, cx);
    const float h = std::numbers::sqrt2_v<float> / 2;
    const float c0 = h * (cx - sx), s0 = h * (sx + cx);  // angle pi/4 + x
    c = q == 0.0f ? c0 : q == 1.0f ? -s0 : q == 2.0f ? -c0 : s0;
    s = q == 0.0f ? s0 : q == 1.0f ? c0 : q == 2.0f ? -s0 : -c0;
}

// The horizon cuts a circle of directions or points, parametrised by an angle t about the
// direction towards the receiver's normal, where toward + across cos t > 0 (across >= 0): the
// half-angle of the arc above it, pi when all of the circle is, about 0 when none is. Never below
// the true arc: a sample past the horizon has weight 0, so the estimate stays unbiased, while an
// arc too short would miss part of the light. Branch-free, so the samplers' loops vectorise.
inline float arcAboveHorizon(float toward, float across) {
    const float x = std::clamp(-toward / std::max(across, 1e-30f), -1.0f, 1.0f);
    return toward - across >= 0.0f ? std::numbers::pi_v<float> : acosUpperBound(x);
}

// sin and cos of t = (2 v - 1) halfAngle for v in [0, 1): uniform over the arc.
inline void sincosOnArc(float v, float halfAngle, float& s, float& c) {
    float turn = (2.0f * v - 1.0f) * halfAngle * (0.5f / std::numbers::pi_v<float>);
    turn = turn < 0.0f ? turn + 1.0f : turn;
    turn = turn >= 1.0f ? 0.0f : turn;
    sincos2Pi(turn, s, c);
}

}  // namespace

// Sutherland-Hodgman against the plane through p with normal n: the part of the rect above p's
// horizon, as a fan of triangles with their cumulative area shares.
static void clipRectToHorizon(const AreaLight& light, const glm::dvec3& p, const glm::dvec3& n,
                              AreaPixel& px) {
    glm::dvec3 in[4];
    double d[4];
    bool allAbove = true;
    for (int k = 0; k < 4; ++k) {
        const double su = (k == 0 || k == 3) ? -0.5 : 0.5, sv = k < 2 ? -0.5 : 0.5;
        in[k] = light.dCenter + su * light.dU + sv * light.dV;
        d[k] = glm::dot(n, in[k] - p);
        allAbove &= d[k] > 0.0;
    }
    if (allAbove) return;
    glm::dvec3 out[5];
    int m = 0;
    for (int k = 0; k < 4; ++k) {
        const int j = (k + 1) % 4;
        if (d[k] > 0.0) out[m++] = in[k];
        if ((d[k] > 0.0) != (d[j] > 0.0))
            out[m++] = in[k] + (d[k] / (d[k] - d[j])) * (in[j] - in[k]);
    }
    if (m < 3) return;  // nothing (measurable) above: classifyAreaPixel decides those
    double area[3], total = 0.0;
    const int tris = m - 2;
    for (int t = 0; t < tris; ++t) {
        area[t] = 0.5 * glm::length(glm::cross(out[t + 1] - out[0], out[t + 2] - out[0]));
        total += area[t];
    }
    if (!(total > 0.0)) return;
    double acc = 0.0;
    for (int t = 0; t < tris; ++t) {
        px.tri[t][0] = glm::vec3(out[0]);
        px.tri[t][1] = glm::vec3(out[t + 1]);
        px.tri[t][2] = glm::vec3(out[t + 2]);
        acc += area[t];
        px.triCdf[t] = float(acc / total);
    }
    px.triCdf[tris - 1] = 1.0f;
    px.clippedTriangles = tris;
}

// Where the horizon cuts the sphere's cone: the rings with a part above it, in bins picked in
// proportion to their largest visible half-angle (which is monotone in the ring's angle, so a
// bin's ends bound it), so that samples go where the cap is visible.
static void binVisibleRings(AreaPixel& px) {
    const double c = px.horizonC, s = px.horizonS;
    // Rings nearer the axis than the elevation of its point under the horizon lie wholly below it
    // (for c < 0: theta < -asin(c), 1 - cos = c^2 / (1 + s)); the bins start a hair nearer, as a
    // ring wrongly left out would bias the estimate and one wrongly kept only costs a sample.
    const double yLo = c < 0.0 ? (1.0 - 1e-6) * c * c / (1.0 + s) : 0.0;
    const double yHi = px.oneMinusCosMax;
    px.sphereYLo = float(std::min(yLo, yHi));
    px.sphereBinY = float(std::max(0.0, yHi - yLo) / AreaPixel::kSphereBins);
    float arc[AreaPixel::kSphereBins + 1];
    for (int j = 0; j <= AreaPixel::kSphereBins; ++j) {
        const float y = px.sphereYLo + float(j) * px.sphereBinY;
        const float sinT = std::sqrt(std::max(0.0f, y * (2.0f - y)));
        arc[j] = arcAboveHorizon(px.horizonC * (1.0f - y), px.horizonS * sinT);
    }
    double total = 0.0;
    for (int j = 0; j < AreaPixel::kSphereBins; ++j) {
        // Never 0: every bin keeps a chance, so no visible ring goes unsampled.
        px.sphereBinArc[j] = std::max(arc[j], arc[j + 1]) + 1e-7f;
        total += px.sphereBinArc[j];
    }
    double acc = 0.0;
    for (int j = 0; j < AreaPixel::kSphereBins; ++j) {
        acc += px.sphereBinArc[j];
        px.sphereCdf[j] = float(acc / total);
    }
    px.sphereCdf[AreaPixel::kSphereBins - 1] = 1.0f;
}

static void prepareSphere(const AreaLight& light, const glm::vec3& p, const glm::vec3& n,
                          AreaPixel& px) {
    const glm::dvec3 d = glm::dvec3(light.lsCenter) - glm::dvec3(p);
    const double dist = glm::length(d);
    const glm::dvec3 wc = d / dist;
    const double sin2 = std::min(1.0, (double(light.lsRadius) * light.lsRadius) / (dist * dist));
    const double cosMax = std::sqrt(1.0 - sin2);
    // t1 along the normal's part across the cone's axis: the horizon then cuts each ring of the
    // cone in an arc symmetric about t1, which the sampler skips (mapAreaBatch).
    const glm::dvec3 nd(n), nPerp = nd - glm::dot(nd, wc) * wc;
    const double s = glm::length(nPerp);
    glm::dvec3 helper = std::fabs(wc.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
    const glm::dvec3 t1 = s > 1e-9 ? nPerp / s : glm::normalize(glm::cross(helper, wc));
    const double c = glm::dot(nd, wc);
    px.horizonC = float(c);
    px.horizonS = float(s > 1e-9 ? s : 0.0);
    px.wc = glm::vec3(wc);
    px.t1 = glm::vec3(t1);
    px.t2 = glm::vec3(glm::cross(wc, t1));
    px.dist = float(dist);
    // 1 - cos(theta_max) without cancellation for small, distant spheres.
    px.oneMinusCosMax = float(sin2 / (1.0 + cosMax));
    px.radius2 = light.lsRadius * light.lsRadius;
    // The cone's outermost ring, at its lowest, is above the horizon by c cos - s sin: with a
    // margin over the float sampling's rounding, the whole cone is visible.
    px.sphereClipped = !(c * cosMax - s * std::sqrt(sin2) > 1e-5);
    if (px.sphereClipped) binVisibleRings(px);
}

AreaPixel prepareAreaPixel(const AreaLight& light, const glm::vec3& p, const glm::vec3& n) {
    AreaPixel px;
    px.p = p;
    px.n = n;
    if (light.type == LightType::Rect) clipRectToHorizon(light, glm::dvec3(p), glm::dvec3(n), px);
    if (light.type == LightType::Disk) {
        // Where the horizon crosses the disk, the sampler skips the part below it.
        const glm::dvec3 nd(n);
        const double h = glm::dot(nd, light.dCenter - glm::dvec3(p));
        const double a1 = glm::dot(nd, glm::dvec3(light.lsE1)),
                     a2 = glm::dot(nd, glm::dvec3(light.lsE2));
        const double s = std::sqrt(a1 * a1 + a2 * a2);
        if (s > 1e-9 && h < light.dRadius * s) {
            px.diskClipped = true;
            px.diskH = float(h);
            px.diskS = float(s);
            px.diskA1 = float(a1 / s);
            px.diskA2 = float(a2 / s);
        }
    }
    if (light.type == LightType::Sphere) prepareSphere(light, p, n, px);
    return px;
}

// The direction at ring y = 1 - cos(theta) and angle phi (sin, cos) about the cone's axis, its
// segment to the sphere's near side and its cosine to the receiver.
struct SphereDirection {
    float x, y, z, tfar, cosP;
};
static inline SphereDirection sphereDirection(const AreaPixel& px, float y, float sinPhi,
                                              float cosPhi, float margin) {
    const float cosT = 1.0f - y;
    const float sinT = std::sqrt(std::max(0.0f, y * (2.0f - y)));  // exact for small cones
    const float cx = cosPhi * sinT, cy = sinPhi * sinT;
    SphereDirection d;
    d.x = cx * px.t1.x + cy * px.t2.x + cosT * px.wc.x;
    d.y = cx * px.t1.y + cy * px.t2.y + cosT * px.wc.y;
    d.z = cx * px.t1.z + cy * px.t2.z + cosT * px.wc.z;
    const float disc = std::max(0.0f, px.radius2 - px.dist * px.dist * sinT * sinT);
    d.tfar = std::max(0.0f, px.dist * cosT - std::sqrt(disc) - margin);
    d.cosP = px.n.x * d.x + px.n.y * d.y + px.n.z * d.z;
    return d;
}

// The whole cone above the horizon: uniform in its solid angle, weight cos_p.
SO_SAMPLER_CLONES static void sphereConeBatch(const AreaPixel& px, const float* su, const float* sv,
                                              int count, float margin, AreaBatch& b) {
    for (int k = 0; k < 16; ++k) {
        float sinPhi, cosPhi;
        sincos2Pi(sv[k], sinPhi, cosPhi);
        const SphereDirection d =
            sphereDirection(px, su[k] * px.oneMinusCosMax, sinPhi, cosPhi, margin);
        b.dirX[k] = d.x;
        b.dirY[k] = d.y;
        b.dirZ[k] = d.z;
        b.tfar[k] = d.tfar;
        b.cosine[k] = d.cosP;
        b.weight[k] = ((k < count) & (d.cosP > 0.0f)) ? d.cosP : 0.0f;
    }
}

// The horizon across the cone: a bin of rings by the pixel's table, a ring within it, then the
// angle over the ring's arc above the horizon; the weight carries the arc over its bin's bound.
SO_SAMPLER_CLONES static void sphereCapBatch(const AreaPixel& px, const float* su, const float* sv,
                                             int count, float margin, AreaBatch& b) {
    for (int k = 0; k < 16; ++k) {
        int j = 0;
        for (int e = 0; e + 1 < AreaPixel::kSphereBins; ++e) j += su[k] >= px.sphereCdf[e];
        const float lo = j ? px.sphereCdf[j - 1] : 0.0f;
        // The rest of u places the ring within the bin (keeps the strata).
        const float within =
            std::min(0.99999994f, (su[k] - lo) / std::max(px.sphereCdf[j] - lo, 1e-30f));
        const float y = px.sphereYLo + (float(j) + within) * px.sphereBinY;
        const float sinT = std::sqrt(std::max(0.0f, y * (2.0f - y)));
        const float phiMax = arcAboveHorizon(px.horizonC * (1.0f - y), px.horizonS * sinT);
        float sinPhi, cosPhi;
        sincosOnArc(sv[k], phiMax, sinPhi, cosPhi);
        const SphereDirection d = sphereDirection(px, y, sinPhi, cosPhi, margin);
        b.dirX[k] = d.x;
        b.dirY[k] = d.y;
        b.dirZ[k] = d.z;
        b.tfar[k] = d.tfar;
        b.cosine[k] = d.cosP;
        b.weight[k] =
            ((k < count) & (d.cosP > 0.0f)) ? d.cosP * (phiMax / px.sphereBinArc[j]) : 0.0f;
    }
}

// Points on the light, one branch-free loop per shape; `share` is the weight factor of a sample
// whose circle the horizon cuts (1 elsewhere).
struct LightPoints {
    float x[16], y[16], z[16];
    float share[16];
};

SO_SAMPLER_CLONES static void rectPoints(const AreaLight& light, const float* su, const float* sv,
                                         LightPoints& q) {
    float* yx = q.x;
    float* yy = q.y;
    float* yz = q.z;
    for (int k = 0; k < 16; ++k) {
        const glm::vec3 y =
            light.lsCenter + (su[k] - 0.5f) * light.lsU + (sv[k] - 0.5f) * light.lsV;
        yx[k] = y.x, yy[k] = y.y, yz[k] = y.z;
    }
}

SO_SAMPLER_CLONES static void clippedRectPoints(const AreaPixel& px, const float* su,
                                                const float* sv, LightPoints& q) {
    float* yx = q.x;
    float* yy = q.y;
    float* yz = q.z;
    for (int k = 0; k < 16; ++k) {
        // Pick a triangle by area with u, reuse the rest of u inside it (keeps strata).
        int t = 0;
        while (t + 1 < px.clippedTriangles && su[k] >= px.triCdf[t]) ++t;
        const float lo = t ? px.triCdf[t - 1] : 0.0f;
        const float uu = std::min(0.99999994f, (su[k] - lo) / std::max(px.triCdf[t] - lo, 1e-30f));
        const float r = std::sqrt(uu);
        const glm::vec3 y = (1.0f - r) * px.tri[t][0] + (r * (1.0f - sv[k])) * px.tri[t][1] +
                            (r * sv[k]) * px.tri[t][2];
        yx[k] = y.x, yy[k] = y.y, yz[k] = y.z;
    }
}

SO_SAMPLER_CLONES static void clippedDiskPoints(const AreaLight& light, const AreaPixel& px,
                                                const float* su, const float* sv, LightPoints& q) {
    float* yx = q.x;
    float* yy = q.y;
    float* yz = q.z;
    float* share = q.share;
    for (int k = 0; k < 16; ++k) {
        // Area-uniform radius; the angle over the arc of that circle above the horizon only,
        // the weight carrying the arc's share.
        const float r = light.lsRadius * std::sqrt(su[k]);
        const float tMax = arcAboveHorizon(px.diskH, r * px.diskS);
        share[k] = tMax * (1.0f / std::numbers::pi_v<float>);
        float st, ct;
        sincosOnArc(sv[k], tMax, st, ct);
        const float e1 = r * (ct * px.diskA1 - st * px.diskA2),
                    e2 = r * (ct * px.diskA2 + st * px.diskA1);
        yx[k] = light.lsCenter.x + e1 * light.lsE1.x + e2 * light.lsE2.x;
        yy[k] = light.lsCenter.y + e1 * light.lsE1.y + e2 * light.lsE2.y;
        yz[k] = light.lsCenter.z + e1 * light.lsE1.z + e2 * light.lsE2.z;
    }
}

SO_SAMPLER_CLONES static void diskPoints(const AreaLight& light, const float* su, const float* sv,
                                         LightPoints& q) {
    float* yx = q.x;
    float* yy = q.y;
    float* yz = q.z;
    for (int k = 0; k < 16; ++k) {
        // Shirley-Chiu concentric map: area-preserving and keeps the strata compact. Its angle
        // is within pi/4 of an axis, where the polynomials are accurate.
        const float a = 2.0f * su[k] - 1.0f, c = 2.0f * sv[k] - 1.0f;
        const bool nearX = std::fabs(a) > std::fabs(c);
        const float r = nearX ? a : c;
        const float num = nearX ? c : a, den = nearX ? a : c;
        const float ratio = num / (den == 0.0f ? 1.0f : den);
        float sq, cq;
        sincosQuarterPi((std::numbers::pi_v<float> / 4) * ratio, sq, cq);
        // nearX: angle = pi/4 * ratio; otherwise pi/2 - pi/4 * ratio (cos and sin swap).
        const float cosT = nearX ? cq : sq, sinT = nearX ? sq : cq;
        const float e1 = light.lsRadius * r * cosT, e2 = light.lsRadius * r * sinT;
        yx[k] = light.lsCenter.x + e1 * light.lsE1.x + e2 * light.lsE2.x;
        yy[k] = light.lsCenter.y + e1 * light.lsE1.y + e2 * light.lsE2.y;
        yz[k] = light.lsCenter.z + e1 * light.lsE1.z + e2 * light.lsE2.z;
    }
}

// Directions, segment lengths and weights G / pdf from the points.
SO_SAMPLER_CLONES static void finishBatch(const AreaLight& light, const AreaPixel& px,
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

void mapAreaBatch(const AreaLight& light, const AreaPixel& px, const float* su, const float* sv,
                  int count, AreaBatch& b) {
    const float margin = 2.0f * light.lsEndMargin;
    if (light.type == LightType::Sphere)
        return px.sphereClipped ? sphereCapBatch(px, su, sv, count, margin, b)
                                : sphereConeBatch(px, su, sv, count, margin, b);
    LightPoints q;
    std::fill(q.share, q.share + 16, 1.0f);
    if (light.type == LightType::Rect && px.clippedTriangles == 0)
        rectPoints(light, su, sv, q);
    else if (light.type == LightType::Rect)
        clippedRectPoints(px, su, sv, q);
    else if (px.diskClipped)
        clippedDiskPoints(light, px, su, sv, q);
    else
        diskPoints(light, su, sv, q);
    finishBatch(light, px, q, count, margin, b);
}

}  // namespace so
