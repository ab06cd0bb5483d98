#include "oracle/polygon_visibility.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <initializer_list>

#include <glm/geometric.hpp>
#include <polyclipping/clipper.hpp>

#include "core/error.h"

namespace so {

namespace {

using glm::dvec3;

// The light's (s, t) in [0, 1] as integers: below Clipper's 2^30 "low range", where its
// arithmetic is plain 64-bit and exact.
constexpr double kQuantum = double(1 << 29);

// A convex polygon of a few vertices, on the stack: a triangle or the light's rectangle, clipped by
// at most 6 half-spaces here (the pyramid's sides and the light's plane), each adding at most one
// vertex. The pass clips every candidate triangle of every pixel, so no allocation per clip.
struct SmallPolygon {
    static constexpr size_t kCapacity = 16;
    std::array<dvec3, kCapacity> v;
    size_t n = 0;
    SmallPolygon(std::initializer_list<dvec3> points) {
        for (const dvec3& q : points) push(q);
    }
    void push(const dvec3& q) {
        SO_CHECK_LT(n, kCapacity);
        v[n++] = q;
    }
    const dvec3* begin() const { return v.data(); }
    const dvec3* end() const { return v.data() + n; }
    dvec3* begin() { return v.data(); }
    dvec3* end() { return v.data() + n; }
};

// Sutherland-Hodgman: the part of the convex polygon where dot(normal, x) <= offset.
SmallPolygon clipToHalfSpace(const SmallPolygon& poly, const ExactTracer::HalfSpace& h) {
    SmallPolygon out{};
    for (size_t i = 0; i < poly.n; ++i) {
        const dvec3& a = poly.v[i];
        const dvec3& b = poly.v[(i + 1) % poly.n];
        const double da = glm::dot(h.normal, a) - h.offset, db = glm::dot(h.normal, b) - h.offset;
        if (da <= 0.0) out.push(a);
        if ((da < 0.0 && db > 0.0) || (da > 0.0 && db < 0.0)) {
            const double t = da / (da - db);
            out.push(a + t * (b - a));
        }
    }
    return out;
}

// The same for a polygon of any size (a light region: disk_bounds.h's n-gons).
std::vector<dvec3> clipToHalfSpace(const std::vector<dvec3>& poly,
                                   const ExactTracer::HalfSpace& h) {
    std::vector<dvec3> out;
    out.reserve(poly.size() + 1);
    for (size_t i = 0; i < poly.size(); ++i) {
        const dvec3& a = poly[i];
        const dvec3& b = poly[(i + 1) % poly.size()];
        const double da = glm::dot(h.normal, a) - h.offset, db = glm::dot(h.normal, b) - h.offset;
        if (da <= 0.0) out.push_back(a);
        if ((da < 0.0 && db > 0.0) || (da > 0.0 && db < 0.0)) {
            const double t = da / (da - db);
            out.push_back(a + t * (b - a));
        }
    }
    return out;
}

// The light's frame: (s, t) of a point of its plane, and back.
struct LightFrame {
    dvec3 corner, edgeU, edgeV, emitNormal;
    double invUU = 0.0, invVV = 0.0;
    LightFrame(const dvec3& c, const dvec3& u, const dvec3& v, const dvec3& m)
        : corner(c),
          edgeU(u),
          edgeV(v),
          emitNormal(m),
          invUU(1.0 / glm::dot(u, u)),
          invVV(1.0 / glm::dot(v, v)) {}
    ClipperLib::IntPoint quantised(const dvec3& y) const {
        const dvec3 d = y - corner;
        return {ClipperLib::cInt(std::llround(glm::dot(d, edgeU) * invUU * kQuantum)),
                ClipperLib::cInt(std::llround(glm::dot(d, edgeV) * invVV * kQuantum))};
    }
    dvec3 point(const ClipperLib::IntPoint& q) const {
        return corner + (double(q.X) / kQuantum) * edgeU + (double(q.Y) / kQuantum) * edgeV;
    }
};

template <typename Polygon>
ClipperLib::Path quantisedPath(const LightFrame& frame, const Polygon& poly) {
    ClipperLib::Path path;
    for (const dvec3& y : poly) path.push_back(frame.quantised(y));
    if (!ClipperLib::Orientation(path)) ClipperLib::ReversePath(path);  // all windings alike
    return path;
}

double solidAngleOf(const LightFrame& frame, const dvec3& p, const dvec3& n,
                    const ClipperLib::Path& path) {
    std::vector<dvec3> vertices;
    vertices.reserve(path.size());
    for (const ClipperLib::IntPoint& q : path) vertices.push_back(frame.point(q));
    return cosineWeightedSolidAngle(p, n, vertices);
}

// The pyramid from p to the polygon `base` (convex, in the light's plane): a side half-space per
// edge through p, and the light's plane on p's side.
std::vector<ExactTracer::HalfSpace> pyramid(const dvec3& p, const SmallPolygon& base,
                                            const LightFrame& light) {
    dvec3 centroid(0.0);
    for (const dvec3& b : base) centroid += b;
    centroid /= double(base.n);
    std::vector<ExactTracer::HalfSpace> planes;
    for (size_t i = 0; i < base.n; ++i) {
        dvec3 m = glm::cross(base.v[i] - p, base.v[(i + 1) % base.n] - p);
        if (m == dvec3(0.0)) continue;  // a zero-length edge
        if (glm::dot(m, centroid - p) > 0.0) m = -m;
        planes.push_back({m, glm::dot(m, p)});
    }
    planes.push_back({-light.emitNormal, -glm::dot(light.emitNormal, light.corner)});
    return planes;
}

// Whether p lies in the plane of triangle abc (to rounding): its projection through p is then a
// segment, of no area.
bool inPlaneOf(const dvec3& p, const dvec3& a, const dvec3& b, const dvec3& c) {
    const dvec3 normal = glm::cross(b - a, c - a);
    const double scale =
        glm::length(normal) * (glm::length(p - a) + glm::length(p - b) + glm::length(p - c));
    return std::abs(glm::dot(normal, p - a)) <= 1e-13 * scale;
}

// The shadow triangle abc casts on the light from p: clipped to the pyramid, projected centrally
// through p onto the light's plane (every point of the clipped part lies between p and the plane,
// so dot(emitNormal, q - p) is in [-height, 0)), quantised. Empty where nothing is left.
ClipperLib::Path shadowOf(const dvec3& a, const dvec3& b, const dvec3& c, const dvec3& p,
                          double height, const std::vector<ExactTracer::HalfSpace>& planes,
                          const LightFrame& frame) {
    SmallPolygon part{a, b, c};
    for (const ExactTracer::HalfSpace& h : planes) {
        part = clipToHalfSpace(part, h);
        if (part.n < 3) return {};
    }
    for (dvec3& q : part) {
        const double along = glm::dot(frame.emitNormal, q - p);
        if (!(along < 0.0)) return {};  // at p itself: only a triangle through p
        q = p + (q - p) * (-height / along);
    }
    return quantisedPath(frame, part);
}

}  // namespace

double cosineWeightedSolidAngle(const dvec3& p, const dvec3& n,
                                const std::vector<dvec3>& vertices) {
    double sum = 0.0;
    const size_t count = vertices.size();
    for (size_t i = 0; i < count; ++i) {
        const dvec3 a = glm::normalize(vertices[i] - p);
        const dvec3 b = glm::normalize(vertices[(i + 1) % count] - p);
        const dvec3 c = glm::cross(a, b);
        const double sinAngle = glm::length(c);
        if (!(sinAngle > 0.0)) continue;  // a zero-length edge, or one pointing at p
        // atan2, not acos: acos loses digits where the edge subtends a small angle.
        sum += std::atan2(sinAngle, glm::dot(a, b)) * glm::dot(n, c) / sinAngle;
    }
    return 0.5 * sum;
}

PolygonLightShape polygonOf(const RectLightShape& rect) {
    PolygonLightShape shape{rect.corner, rect.edgeU, rect.edgeV, rect.emitNormal, {}};
    shape.vertices = {rect.corner, rect.corner + rect.edgeU, rect.corner + rect.edgeU + rect.edgeV,
                      rect.corner + rect.edgeV};
    return shape;
}

PolygonVisibility rectLightVisibility(const ExactTracer& tracer, const RectLightShape& light,
                                      const dvec3& p, const dvec3& n, TriangleId self,
                                      uint32_t maxCandidates) {
    return polygonLightVisibility(tracer, polygonOf(light), p, n, self, maxCandidates);
}

PolygonVisibility polygonLightVisibility(const ExactTracer& tracer, const PolygonLightShape& light,
                                         const dvec3& p, const dvec3& n, TriangleId self,
                                         uint32_t maxCandidates) {
    const LightShadows shadows(tracer, light, p, n, self, maxCandidates);
    PolygonVisibility result = shadows.counts();
    if (result.status == PolygonVisibilityStatus::Exact) result.V = shadows.baseV();
    return result;
}

LightShadows::LightShadows(const ExactTracer& tracer, const PolygonLightShape& base, const dvec3& p,
                           const dvec3& n, TriangleId self, uint32_t maxCandidates)
    : corner_(base.corner),
      edgeU_(base.edgeU),
      edgeV_(base.edgeV),
      emitNormal_(base.emitNormal),
      p_(p),
      n_(n) {
    SO_CHECK_LE(base.vertices.size(), PolygonLightShape::kMaxVertices);
    height_ = glm::dot(base.emitNormal, p - base.corner);  // > 0 on the lit side
    if (!(height_ > 0.0)) return;
    // L+: the light above p's horizon.
    SmallPolygon whole{};
    for (const dvec3& v : base.vertices) whole.push(v);
    const SmallPolygon lit = clipToHalfSpace(whole, {-n, -glm::dot(n, p)});
    if (lit.n < 3) return;
    const LightFrame frame(corner_, edgeU_, edgeV_, emitNormal_);
    litPath_ = quantisedPath(frame, lit);
    litWhole_ = solidAngleOf(frame, p, n, litPath_);
    if (!(std::abs(litWhole_) > 0.0)) return;
    lit_.assign(lit.begin(), lit.end());
    gather(tracer, self, maxCandidates);
}

void LightShadows::gather(const ExactTracer& tracer, TriangleId self, uint32_t maxCandidates) {
    const LightFrame frame(corner_, edgeU_, edgeV_, emitNormal_);
    SmallPolygon lit{};
    for (const dvec3& v : lit_) lit.push(v);
    const std::vector<ExactTracer::HalfSpace> planes = pyramid(p_, lit, frame);
    bool capped = false, alpha = false;
    PolygonVisibility& result = result_;
    const auto visit = [&](const dvec3& a, const dvec3& b, const dvec3& c, TriangleId id) {
        if (++result.candidates > maxCandidates) {
            capped = true;
            return false;
        }
        if (id == self || inPlaneOf(p_, a, b, c)) return true;
        ClipperLib::Path shadow = shadowOf(a, b, c, p_, height_, planes, frame);
        if (!shadow.empty() && tracer.alphaTested(id)) {
            alpha = true;
            return false;
        }
        if (!shadow.empty()) {
            shadows_.push_back(std::move(shadow));
            ++result.occluders;
        }
        return true;
    };
    tracer.forEachTriangleIn(planes, visit);
    if (capped || alpha) {
        result.status = capped ? PolygonVisibilityStatus::TooManyOccluders
                               : PolygonVisibilityStatus::AlphaTested;
        return;
    }
    result.status = PolygonVisibilityStatus::Exact;
}

namespace {

// Phi(subject minus the clips), >= 0.
double visibleSolidAngle(const LightFrame& frame, const dvec3& p, const dvec3& n,
                         const ClipperLib::Path& subject, const ClipperLib::Paths& clips) {
    ClipperLib::Clipper clipper;
    clipper.AddPath(subject, ClipperLib::ptSubject, true);
    clipper.AddPaths(clips, ClipperLib::ptClip, true);
    ClipperLib::Paths visible;
    clipper.Execute(ClipperLib::ctDifference, visible, ClipperLib::pftNonZero,
                    ClipperLib::pftNonZero);
    double seen = 0.0;
    for (const ClipperLib::Path& path : visible) seen += solidAngleOf(frame, p, n, path);
    return seen;
}

}  // namespace

double LightShadows::baseV() const {
    SO_CHECK(result_.status == PolygonVisibilityStatus::Exact);
    if (shadows_.empty()) return 1.0;
    const LightFrame frame(corner_, edgeU_, edgeV_, emitNormal_);
    const double seen = visibleSolidAngle(frame, p_, n_, litPath_, shadows_);
    return std::clamp(seen / litWhole_, 0.0, 1.0);
}

LightShadows::Integrals LightShadows::integrals(const std::vector<dvec3>& region) const {
    Integrals out;
    if (result_.status == PolygonVisibilityStatus::NoLight) return out;
    SO_CHECK(result_.status == PolygonVisibilityStatus::Exact);
    const std::vector<dvec3> lit = clipToHalfSpace(region, {-n_, -glm::dot(n_, p_)});
    if (lit.size() < 3) return out;
    const LightFrame frame(corner_, edgeU_, edgeV_, emitNormal_);
    const ClipperLib::Path path = quantisedPath(frame, lit);
    // Signed by the path's winding (quantisedPath makes it Clipper's positive one), as are the
    // visible parts Clipper returns.
    const double signedWhole = solidAngleOf(frame, p_, n_, path);
    const double sign = signedWhole < 0.0 ? -1.0 : 1.0;
    out.whole = sign * signedWhole;
    if (shadows_.empty()) {
        out.visible = out.whole;
        return out;
    }
    if (!united_) {
        // Once for every region: the regions differ only near the light's outline.
        ClipperLib::Clipper clipper;
        clipper.AddPaths(shadows_, ClipperLib::ptSubject, true);
        clipper.Execute(ClipperLib::ctUnion, union_, ClipperLib::pftNonZero,
                        ClipperLib::pftNonZero);
        united_ = true;
    }
    out.visible = std::max(0.0, sign * visibleSolidAngle(frame, p_, n_, path, union_));
    return out;
}

}  // namespace so
