// The oracle's sphere light (docs/oracle.md): sampled in the solid angle of its visible cap
// (where the horizon cuts the cone, only the rings with a part above it); the exact pass takes it
// as the disk of its silhouette (disk_bounds.h) and integrates that exactly (disk_exact.h).
#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <numbers>

#include <glm/geometric.hpp>

#include "oracle/area_light.h"
#include "oracle/disk_bounds.h"
#include "oracle/disk_exact.h"
#include "oracle/exact_penumbra.h"
#include "oracle/lights/area_light_kind.h"
#include "oracle/lights/area_sampling.h"
#include "oracle/near_field.h"
#include "oracle/reference_light.h"

namespace so {

namespace {

// Where the horizon cuts the sphere's cone: the rings with a part above it, in bins picked in
// proportion to their largest visible half-angle (which is monotone in the ring's angle, so a
// bin's ends bound it), so that samples go where the cap is visible.
void binVisibleRings(AreaPixel& px) {
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

void prepareSphere(const AreaLight& light, const glm::vec3& p, const glm::vec3& n, AreaPixel& px) {
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

// The direction at ring y = 1 - cos(theta) and angle phi (sin, cos) about the cone's axis, its
// segment to the sphere's near side and its cosine to the receiver.
struct SphereDirection {
    float x, y, z, tfar, cosP;
};
inline SphereDirection sphereDirection(const AreaPixel& px, float y, float sinPhi, float cosPhi,
                                       float margin) {
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
SO_SAMPLER_CLONES void sphereConeBatch(const AreaPixel& px, const float* su, const float* sv,
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
SO_SAMPLER_CLONES void sphereCapBatch(const AreaPixel& px, const float* su, const float* sv,
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

// The verifier's independent samples: uniform by area over the whole sphere.
class SphereReference final : public ReferenceSampler {
  public:
    SphereReference(const Light& light, const LocalFrame& frame)
        : c_(frame.lsFromWs(light.wsPosition)), radius_(light.radius * frame.lsLength(1.0)) {}
    void point(double u1, double u2, glm::dvec3& y, glm::dvec3& ny) const override {
        const double zc = 1.0 - 2.0 * u1, rr = std::sqrt(std::max(0.0, 1.0 - zc * zc));
        const double phi = 2.0 * std::numbers::pi * u2;
        ny = glm::dvec3(rr * std::cos(phi), rr * std::sin(phi), zc);
        y = c_ + radius_ * ny;
    }

  private:
    glm::dvec3 c_;
    double radius_;
};

class SphereAreaLightKind final : public AreaLightKind {
  public:
    LightType type() const override { return LightType::Sphere; }
    double extent(const AreaLight& a) const override { return a.dRadius; }
    AreaSkip classify(const AreaLight& light, const glm::dvec3& p, const glm::dvec3& n,
                      const PixelTies*) const override {
        // A sphere has no plane to lie in: its centre in the receiver's plane is above it by
        // the radius.
        const glm::dvec3 d = light.dCenter - p;
        if (glm::dot(d, d) <= light.dRadius * light.dRadius) return AreaSkip::InsideLight;
        return glm::dot(n, d) + light.dRadius > 0.0 ? AreaSkip::None : AreaSkip::BelowHorizon;
    }
    void preparePixel(const AreaLight& light, const glm::vec3& p, const glm::vec3& n,
                      AreaPixel& px) const override {
        prepareSphere(light, p, n, px);
    }
    void mapBatch(const AreaLight&, const AreaPixel& px, const float* su, const float* sv,
                  int count, float margin, AreaBatch& b) const override {
        if (px.sphereClipped)
            sphereCapBatch(px, su, sv, count, margin, b);
        else
            sphereConeBatch(px, su, sv, count, margin, b);
    }
    // The cube around it.
    NearTarget nearTarget(const AreaLight& light) const override {
        NearTarget t;
        for (int k = 0; k < 8; ++k)
            t.points[k] = light.dCenter + light.dRadius * glm::dvec3(k & 1 ? 1 : -1, k & 2 ? 1 : -1,
                                                                     k & 4 ? 1 : -1);
        t.count = 8;
        return t;
    }
    const char* sampling() const override { return "solid angle of the visible cap"; }
    bool bounded() const override { return true; }
    ExactLightAnswer exactAt(const ExactTracer& tracer, const AreaLight& light,
                             const ExactPenumbraOptions& options, const OccluderOptions& more,
                             const glm::dvec3& p, const glm::dvec3& n,
                             TriangleId self) const override {
        const glm::dvec3 w = light.dCenter - p;
        if (!(glm::dot(w, w) > light.dRadius * light.dRadius)) return {};  // inside: NoLight
        const DiskLightShape disk = sphereSilhouette(light.dCenter, light.dRadius, p);
        return diskAnswer(diskLightExact(tracer, disk, p, n, self, options.maxOccluders, more),
                          options.bound);
    }
    std::shared_ptr<const ReferenceSampler> reference(const Light& l,
                                                      const LocalFrame& f) const override {
        return std::make_shared<SphereReference>(l, f);
    }
    // Its silhouette disk from p; none from inside.
    bool boundedDisk(const Light& l, const LocalFrame& frame, const glm::dvec3& p,
                     DiskLightShape& disk) const override {
        const glm::dvec3 center = frame.lsFromWs(l.wsPosition);
        const double radius = frame.lsLength(l.radius);
        const glm::dvec3 w = center - p;
        if (!(glm::dot(w, w) > radius * radius)) return false;
        disk = sphereSilhouette(center, radius, p);
        return true;
    }
};

}  // namespace

SO_REGISTER_AREA_LIGHT_KIND(SphereAreaLightKind);

}  // namespace so
