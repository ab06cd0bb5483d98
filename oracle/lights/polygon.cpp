// The oracle's polygon light (docs/oracle.md): a planar convex polygon of 3 to 64 vertices
// (core/lights/polygon.cpp checks it). Sampled uniformly by area over its fan of triangles from
// vertex 0: a triangle picked by its share of the area with u, the rest of u and v placing the
// point in it (pdf 1 / area everywhere, as the rect's), not clipped to the horizon: samples below
// it have weight 0 (cos_p <= 0), which keeps the estimate unbiased. Exact by polygon_visibility.h:
// directly up to PolygonLightShape::kMaxVertices, and beyond as a region of its bounding rectangle
// (LightShadows::integrals takes any number of vertices).
#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

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

// The verifier's independent samples: a triangle of its fan from vertex 0 by area, then uniform in
// it.
class PolygonReference final : public ReferenceSampler {
  public:
    PolygonReference(const Light& light, const LocalFrame& frame) : m_(light.wsEmitNormal()) {
        for (const glm::dvec3& w : light.wsVertices) vertices_.push_back(frame.lsFromWs(w));
        double total = 0.0;
        for (size_t k = 1; k + 1 < vertices_.size(); ++k) {
            const glm::dvec3 a = vertices_[k] - vertices_[0], b = vertices_[k + 1] - vertices_[0];
            fanCdf_.push_back(total += glm::length(glm::cross(a, b)));
        }
        for (double& f : fanCdf_) f /= total;
    }
    void point(double u1, double u2, glm::dvec3& y, glm::dvec3& ny) const override {
        size_t t = 0;
        while (t + 1 < fanCdf_.size() && u1 >= fanCdf_[t]) ++t;
        const double lo = t ? fanCdf_[t - 1] : 0.0;
        const double r = std::sqrt(std::min(1.0, (u1 - lo) / (fanCdf_[t] - lo)));
        y = (1.0 - r) * vertices_[0] + r * (1.0 - u2) * vertices_[t + 1] +
            r * u2 * vertices_[t + 2];
        ny = m_;
    }

  private:
    glm::dvec3 m_;
    std::vector<glm::dvec3> vertices_;  // local frame
    std::vector<double> fanCdf_;        // cumulative area shares
};

class PolygonAreaLightKind final : public AreaLightKind {
  public:
    LightType type() const override { return LightType::Polygon; }
    void init(AreaLight& a, const LocalFrame& frame) const override {
        for (const glm::dvec3& v : a.ws.wsVertices) a.dVertices.push_back(frame.lsFromWs(v));
        const std::vector<glm::dvec3>& v = a.dVertices;
        double total = 0.0;
        std::vector<double> areas;
        for (size_t k = 1; k + 1 < v.size(); ++k) {
            areas.push_back(0.5 * glm::length(glm::cross(v[k] - v[0], v[k + 1] - v[0])));
            total += areas.back();
            for (const glm::dvec3& corner : {v[0], v[k], v[k + 1]})
                a.lsFan.push_back(glm::vec3(corner));
        }
        double acc = 0.0;
        for (double area : areas) a.fanCdf.push_back(float((acc += area) / total));
        a.fanCdf.back() = 1.0f;
        // The bounding rectangle along the first edge, for the exact pass's frame.
        const glm::dvec3 e1 = glm::normalize(v[1] - v[0]), e2 = glm::cross(a.dEmitNormal, e1);
        double s0 = 0.0, s1 = 0.0, t0 = 0.0, t1 = 0.0;
        for (const glm::dvec3& x : v) {
            const double s = glm::dot(x - v[0], e1), t = glm::dot(x - v[0], e2);
            s0 = std::min(s0, s), s1 = std::max(s1, s), t0 = std::min(t0, t), t1 = std::max(t1, t);
        }
        a.dBoxCorner = v[0] + s0 * e1 + t0 * e2;
        a.dBoxU = (s1 - s0) * e1;
        a.dBoxV = (t1 - t0) * e2;
    }
    double extent(const AreaLight& a) const override {
        double far = 0.0;
        for (const glm::dvec3& v : a.dVertices) far = std::max(far, glm::length(v - a.dCenter));
        return far;
    }
    AreaSkip classify(const AreaLight& light, const glm::dvec3& p, const glm::dvec3& n,
                      const PixelTies* ties) const override {
        double top = -std::numeric_limits<double>::infinity(), reach = 0.0;
        for (const glm::dvec3& v : light.dVertices) {
            top = std::max(top, glm::dot(n, v - p));
            reach = std::max(reach, glm::length(v - p));
        }
        return classifyOneSidedPixel(light, p, ties, top, reach);
    }
    void mapBatch(const AreaLight& light, const AreaPixel& px, const float* su, const float* sv,
                  int count, float margin, AreaBatch& b) const override {
        LightPoints q;
        std::fill(q.share, q.share + 16, 1.0f);
        fanAreaPoints(light.lsFan.data(), light.fanCdf.data(), int(light.fanCdf.size()), su, sv, q);
        finishAreaBatch(light, px, q, count, margin, b);
    }
    NearTarget nearTarget(const AreaLight& light) const override {
        NearTarget t;
        for (int k = 0; k < 4; ++k)
            t.points[k] = light.dBoxCorner + (k & 1 ? light.dBoxU : glm::dvec3(0.0)) +
                          (k & 2 ? light.dBoxV : glm::dvec3(0.0));
        t.count = 4;
        return t;
    }
    ExactLightAnswer exactAt(const ExactTracer& tracer, const AreaLight& light,
                             const ExactPenumbraOptions& options, const OccluderOptions& more,
                             const glm::dvec3& p, const glm::dvec3& n,
                             TriangleId self) const override {
        PolygonLightShape shape{light.dBoxCorner, light.dBoxU, light.dBoxV, light.dEmitNormal, {}};
        ExactLightAnswer a;
        if (light.dVertices.size() <= PolygonLightShape::kMaxVertices) {
            shape.vertices = light.dVertices;
            a.result =
                polygonLightVisibility(tracer, shape, p, n, self, options.maxOccluders, more);
            return a;
        }
        // Too many sides for the pyramid's fixed buffers: the shadows through the bounding
        // rectangle's pyramid, integrated over the polygon.
        const glm::dvec3 c = shape.corner, u = shape.edgeU, v = shape.edgeV;
        shape.vertices = {c, c + u, c + u + v, c + v};
        const LightShadows shadows(tracer, shape, p, n, self, options.maxOccluders, more);
        a.result = shadows.counts();
        if (a.result.status != PolygonVisibilityStatus::Exact) return a;
        const LightShadows::Integrals in = shadows.integrals(light.dVertices);
        if (!(in.whole > 0.0)) {
            a.result.status = PolygonVisibilityStatus::NoLight;
            return a;
        }
        a.result.V = std::clamp(in.visible / in.whole, 0.0, 1.0);
        return a;
    }
    // Its plane: through its first vertex with its (rounded) normal, as a disk's.
    int sideOfPlane(const Light& l, const glm::dvec3& q) const override {
        return exact::sideOfPlane(l.wsVertices[0], l.wsNormal, q);
    }
    bool abovePlane(const PixelTriangle& t, const Light& l) const override {
        for (const glm::dvec3& v : l.wsVertices)
            if (exact::orient(t.a, t.b, t.c, v) > 0) return true;
        return false;
    }
    std::shared_ptr<const ReferenceSampler> reference(const Light& l,
                                                      const LocalFrame& f) const override {
        return std::make_shared<PolygonReference>(l, f);
    }
};

}  // namespace

SO_REGISTER_AREA_LIGHT_KIND(PolygonAreaLightKind);

}  // namespace so
