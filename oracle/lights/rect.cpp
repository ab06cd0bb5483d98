// The oracle's rect light (docs/oracle.md): sampled uniformly by area, the part above the
// receiver's horizon only (clipped per pixel to a fan of up to 3 triangles); exact by
// polygon_visibility.h on its 4-gon.
#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <numbers>

#include <glm/geometric.hpp>

#include "oracle/area_light.h"
#include "oracle/exact_facing.h"
#include "oracle/exact_penumbra.h"
#include "oracle/exact_sign.h"
#include "oracle/lights/area_light_kind.h"
#include "oracle/lights/area_sampling.h"
#include "oracle/near_field.h"
#include "oracle/reference_light.h"

namespace so {

namespace {

// Sutherland-Hodgman against the plane through p with normal n: the part of the rect above p's
// horizon, as a fan of triangles with their cumulative area shares.
void clipRectToHorizon(const AreaLight& light, const glm::dvec3& p, const glm::dvec3& n,
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

SO_SAMPLER_CLONES void rectPoints(const AreaLight& light, const float* su, const float* sv,
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

// The verifier's independent samples: uniform by area over centre + [-1/2, 1/2] u + [-1/2, 1/2] v.
class RectReference final : public ReferenceSampler {
  public:
    RectReference(const Light& light, const LocalFrame& frame)
        : c_(frame.lsFromWs(light.wsPosition)), m_(light.wsEmitNormal()) {
        const double s = frame.lsLength(1.0);
        u_ = light.wsU * s;
        v_ = light.wsV * s;
    }
    void point(double u1, double u2, glm::dvec3& y, glm::dvec3& ny) const override {
        y = c_ + (u1 - 0.5) * u_ + (u2 - 0.5) * v_;
        ny = m_;
    }

  private:
    glm::dvec3 c_, m_, u_{0.0}, v_{0.0};
};

class RectAreaLightKind final : public AreaLightKind {
  public:
    LightType type() const override { return LightType::Rect; }
    double extent(const AreaLight& a) const override {
        return 0.5 * (glm::length(a.dU) + glm::length(a.dV));
    }
    AreaSkip classify(const AreaLight& light, const glm::dvec3& p, const glm::dvec3& n,
                      const PixelTies* ties) const override {
        const glm::dvec3 c = light.dCenter;
        double top = -std::numeric_limits<double>::infinity(), reach = 0.0;
        for (int k = 0; k < 4; ++k) {
            glm::dvec3 corner =
                c + ((k & 1) ? 0.5 : -0.5) * light.dU + ((k & 2) ? 0.5 : -0.5) * light.dV;
            top = std::max(top, glm::dot(n, corner - p));
            reach = std::max(reach, glm::length(corner - p));
        }
        return classifyOneSidedPixel(light, p, ties, top, reach);
    }
    void preparePixel(const AreaLight& light, const glm::vec3& p, const glm::vec3& n,
                      AreaPixel& px) const override {
        clipRectToHorizon(light, glm::dvec3(p), glm::dvec3(n), px);
    }
    void mapBatch(const AreaLight& light, const AreaPixel& px, const float* su, const float* sv,
                  int count, float margin, AreaBatch& b) const override {
        LightPoints q;
        std::fill(q.share, q.share + 16, 1.0f);
        if (px.clippedTriangles == 0)
            rectPoints(light, su, sv, q);
        else
            fanAreaPoints(&px.tri[0][0], px.triCdf, px.clippedTriangles, su, sv, q);
        finishAreaBatch(light, px, q, count, margin, b);
    }
    NearTarget nearTarget(const AreaLight& light) const override {
        NearTarget t;
        const glm::dvec3 u = 0.5 * light.dU, v = 0.5 * light.dV;
        for (int k = 0; k < 4; ++k)
            t.points[k] = light.dCenter + (k & 1 ? u : -u) + (k & 2 ? v : -v);
        t.count = 4;
        return t;
    }
    ExactLightAnswer exactAt(const ExactTracer& tracer, const AreaLight& light,
                             const ExactPenumbraOptions& options, const OccluderOptions& more,
                             const glm::dvec3& p, const glm::dvec3& n,
                             TriangleId self) const override {
        const RectLightShape shape{light.dCenter - 0.5 * light.dU - 0.5 * light.dV, light.dU,
                                   light.dV, light.dEmitNormal};
        ExactLightAnswer a;
        a.result = rectLightVisibility(tracer, shape, p, n, self, options.maxOccluders, more);
        return a;
    }
    // Its plane is the span of its edges (its unit normal is rounded; the span is not).
    int sideOfPlane(const Light& l, const glm::dvec3& q) const override {
        return exact::sideOfSpan(l.wsPosition, l.wsU, l.wsV, q);
    }
    bool abovePlane(const PixelTriangle& t, const Light& l) const override {
        // Corners centre +- u/2 +- v/2: halving a double is exact, the sum is taken exactly.
        for (int k = 0; k < 4; ++k) {
            const glm::dvec3 hu = ((k & 1) ? 0.5 : -0.5) * l.wsU;
            const glm::dvec3 hv = ((k & 2) ? 0.5 : -0.5) * l.wsV;
            if (exact::orient(t.a, t.b, t.c, l.wsPosition, hu, hv) > 0) return true;
        }
        return false;
    }
    std::shared_ptr<const ReferenceSampler> reference(const Light& l,
                                                      const LocalFrame& f) const override {
        return std::make_shared<RectReference>(l, f);
    }
};

}  // namespace

SO_REGISTER_AREA_LIGHT_KIND(RectAreaLightKind);

}  // namespace so
