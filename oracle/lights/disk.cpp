// The oracle's disk light (docs/oracle.md): sampled uniformly by area (Shirley-Chiu's concentric
// map; where the horizon crosses it, each circle over its arc above the horizon); the exact pass
// clips the shadows against its circle and integrates the arcs (disk_exact.h).
#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <numbers>

#include <glm/geometric.hpp>

#include "oracle/area_light.h"
#include "oracle/disk_bounds.h"
#include "oracle/disk_exact.h"
#include "oracle/exact_facing.h"
#include "oracle/exact_penumbra.h"
#include "oracle/exact_sign.h"
#include "oracle/lights/area_light_kind.h"
#include "oracle/lights/area_sampling.h"
#include "oracle/near_field.h"
#include "oracle/reference_light.h"

namespace so {

namespace {

SO_SAMPLER_CLONES void clippedDiskPoints(const AreaLight& light, const AreaPixel& px,
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

SO_SAMPLER_CLONES void diskPoints(const AreaLight& light, const float* su, const float* sv,
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

// The verifier's independent samples: uniform by area, r = R sqrt(u1) (no concentric map, unlike
// the sampled pass, so that the two share nothing).
class DiskReference final : public ReferenceSampler {
  public:
    DiskReference(const Light& light, const LocalFrame& frame)
        : c_(frame.lsFromWs(light.wsPosition)),
          m_(light.wsEmitNormal()),
          radius_(light.radius * frame.lsLength(1.0)) {
        const glm::dvec3 helper = std::fabs(m_.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
        e1_ = glm::normalize(glm::cross(helper, m_));
        e2_ = glm::cross(m_, e1_);
    }
    void point(double u1, double u2, glm::dvec3& y, glm::dvec3& ny) const override {
        const double r = radius_ * std::sqrt(u1), phi = 2.0 * std::numbers::pi * u2;
        y = c_ + r * (std::cos(phi) * e1_ + std::sin(phi) * e2_);
        ny = m_;
    }

  private:
    glm::dvec3 c_, m_, e1_{0.0}, e2_{0.0};
    double radius_;
};

class DiskAreaLightKind final : public AreaLightKind {
  public:
    LightType type() const override { return LightType::Disk; }
    void init(AreaLight& a, const LocalFrame&) const override {
        glm::dvec3 m = a.dEmitNormal;
        glm::dvec3 helper = std::fabs(m.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
        glm::dvec3 e1 = glm::normalize(glm::cross(helper, m));
        a.lsE1 = glm::vec3(e1);
        a.lsE2 = glm::vec3(glm::cross(m, e1));
    }
    double extent(const AreaLight& a) const override { return a.dRadius; }
    AreaSkip classify(const AreaLight& light, const glm::dvec3& p, const glm::dvec3& n,
                      const PixelTies* ties) const override {
        // The disk's highest point above p's tangent plane.
        const glm::dvec3 c = light.dCenter;
        const double nm = glm::dot(n, light.dEmitNormal);
        const double top =
            glm::dot(n, c - p) + light.dRadius * std::sqrt(std::max(0.0, 1.0 - nm * nm));
        return classifyOneSidedPixel(light, p, ties, top, glm::length(c - p) + light.dRadius);
    }
    void preparePixel(const AreaLight& light, const glm::vec3& p, const glm::vec3& n,
                      AreaPixel& px) const override {
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
    void mapBatch(const AreaLight& light, const AreaPixel& px, const float* su, const float* sv,
                  int count, float margin, AreaBatch& b) const override {
        LightPoints q;
        std::fill(q.share, q.share + 16, 1.0f);
        if (px.diskClipped)
            clippedDiskPoints(light, px, su, sv, q);
        else
            diskPoints(light, su, sv, q);
        finishAreaBatch(light, px, q, count, margin, b);
    }
    // Its circumscribed square in its plane.
    NearTarget nearTarget(const AreaLight& light) const override {
        NearTarget t;
        const glm::dvec3 u = light.dRadius * glm::dvec3(light.lsE1),
                         v = light.dRadius * glm::dvec3(light.lsE2);
        for (int k = 0; k < 4; ++k)
            t.points[k] = light.dCenter + (k & 1 ? u : -u) + (k & 2 ? v : -v);
        t.count = 4;
        return t;
    }
    bool bounded() const override { return true; }
    ExactLightAnswer exactAt(const ExactTracer& tracer, const AreaLight& light,
                             const ExactPenumbraOptions& options, const OccluderOptions& more,
                             const glm::dvec3& p, const glm::dvec3& n,
                             TriangleId self) const override {
        DiskLightShape disk;
        disk.center = light.dCenter;
        disk.radius = light.dRadius;
        disk.emitNormal = light.dEmitNormal;
        diskAxes(disk.emitNormal, disk.e1, disk.e2);
        return diskAnswer(diskLightExact(tracer, disk, p, n, self, options.maxOccluders, more),
                          options.bound);
    }
    // Its plane: through its centre with its (rounded) normal.
    int sideOfPlane(const Light& l, const glm::dvec3& q) const override {
        return exact::sideOfPlane(l.wsPosition, l.wsNormal, q);
    }
    bool abovePlane(const PixelTriangle& t, const Light& l) const override {
        return exact::diskAbovePlane(t.a, t.b, t.c, l.wsPosition, l.wsNormal, l.radius);
    }
    std::shared_ptr<const ReferenceSampler> reference(const Light& l,
                                                      const LocalFrame& f) const override {
        return std::make_shared<DiskReference>(l, f);
    }
    bool boundedDisk(const Light& l, const LocalFrame& frame, const glm::dvec3&,
                     DiskLightShape& disk) const override {
        disk.center = frame.lsFromWs(l.wsPosition);
        disk.radius = frame.lsLength(l.radius);
        disk.emitNormal = l.wsEmitNormal();
        diskAxes(disk.emitNormal, disk.e1, disk.e2);
        return true;
    }
};

}  // namespace

ExactLightAnswer diskAnswer(const DiskExactVisibility& d, const DiskBoundOptions& options) {
    ExactLightAnswer a;
    a.result = d.counts;
    a.halfWidth = d.error;
    a.sides = d.sides;  // the gathering octagon's, where the contour was integrated
    a.reachedTarget = d.error <= options.targetHalfWidth;
    return a;
}

SO_REGISTER_AREA_LIGHT_KIND(DiskAreaLightKind);

}  // namespace so
