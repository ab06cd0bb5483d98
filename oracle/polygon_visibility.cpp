#include "oracle/polygon_visibility.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <polyclipping/clipper.hpp>

#include "core/error.h"
#include "oracle/small_polygon.h"

namespace so {

namespace {

using glm::dvec3;

double solidAngleOf(const LightPlaneFrame& frame, const dvec3& p, const dvec3& n,
                    const ClipperLib::Path& path) {
    std::vector<dvec3> vertices;
    vertices.reserve(path.size());
    for (const ClipperLib::IntPoint& q : path) vertices.push_back(frame.point(q));
    return cosineWeightedSolidAngle(p, n, vertices);
}

// Phi(subject minus the clips): signed as the subject's winding, as are the parts Clipper returns.
double visibleSolidAngle(const LightPlaneFrame& frame, const dvec3& p, const dvec3& n,
                         const ClipperLib::Path& subject, const ClipperLib::Paths& clips) {
    double seen = 0.0;
    for (const ClipperLib::Path& path : lightMinusShadows(subject, clips))
        seen += solidAngleOf(frame, p, n, path);
    return seen;
}

// The pyramid from p to the polygon `base` (convex, in the light's plane): a side half-space per
// edge through p, and the light's plane on p's side.
std::vector<ExactTracer::HalfSpace> pyramid(const dvec3& p, const SmallPolygon& base,
                                            const LightPlaneFrame& light) {
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
    planes.push_back({-light.emitNormal, -glm::dot(light.emitNormal, light.origin)});
    return planes;
}

}  // namespace

double cosineWeightedSolidAngle(const dvec3& p, const dvec3& n,
                                const std::vector<dvec3>& vertices) {
    double sum = 0.0;
    const size_t count = vertices.size();
    for (size_t i = 0; i < count; ++i)
        sum += lambertEdge(vertices[i] - p, vertices[(i + 1) % count] - p, n);
    return sum;
}

double lambertEdge(const dvec3& a, const dvec3& b, const dvec3& n) {
    const dvec3 ua = glm::normalize(a), ub = glm::normalize(b);
    const dvec3 c = glm::cross(ua, ub);
    const double sinAngle = glm::length(c);
    if (!(sinAngle > 0.0)) return 0.0;  // a zero-length edge, or one pointing at p
    // atan2, not acos: acos loses digits where the edge subtends a small angle.
    return 0.5 * (std::atan2(sinAngle, glm::dot(ua, ub)) * glm::dot(n, c) / sinAngle);
}

PolygonLightShape polygonOf(const RectLightShape& rect) {
    PolygonLightShape shape{rect.corner, rect.edgeU, rect.edgeV, rect.emitNormal, {}};
    shape.vertices = {rect.corner, rect.corner + rect.edgeU, rect.corner + rect.edgeU + rect.edgeV,
                      rect.corner + rect.edgeV};
    return shape;
}

PolygonVisibility rectLightVisibility(const ExactTracer& tracer, const RectLightShape& light,
                                      const dvec3& p, const dvec3& n, TriangleId self,
                                      uint32_t maxCandidates, const OccluderOptions& more) {
    return polygonLightVisibility(tracer, polygonOf(light), p, n, self, maxCandidates, more);
}

PolygonVisibility polygonLightVisibility(const ExactTracer& tracer, const PolygonLightShape& light,
                                         const dvec3& p, const dvec3& n, TriangleId self,
                                         uint32_t maxCandidates, const OccluderOptions& more) {
    const LightShadows shadows(tracer, light, p, n, self, maxCandidates, more);
    PolygonVisibility result = shadows.counts();
    if (result.status == PolygonVisibilityStatus::Exact) result.V = shadows.baseV();
    return result;
}

LightShadows::LightShadows(const ExactTracer& tracer, const PolygonLightShape& base, const dvec3& p,
                           const dvec3& n, TriangleId self, uint32_t maxCandidates,
                           const OccluderOptions& more)
    : frame_(base.corner, base.edgeU, base.edgeV, base.emitNormal), p_(p), n_(n) {
    SO_CHECK_LE(base.vertices.size(), PolygonLightShape::kMaxVertices);
    const double height = glm::dot(base.emitNormal, p - base.corner);  // > 0 on the lit side
    if (!(height > 0.0)) return;
    // L+: the light above p's horizon.
    SmallPolygon whole{};
    for (const dvec3& v : base.vertices) whole.push(v);
    const SmallPolygon lit = clipToHalfSpace(whole, {-n, -glm::dot(n, p)});
    if (lit.n < 3) return;
    litPath_ = frame_.path(lit);
    litWhole_ = solidAngleOf(frame_, p, n, litPath_);
    if (!(std::abs(litWhole_) > 0.0)) return;

    const std::vector<ExactTracer::HalfSpace> planes = pyramid(p, lit, frame_);
    OccluderQuery q;
    q.p = p;
    q.self = self;
    q.height = height;
    q.pyramid = &planes;
    q.frame = &frame_;
    q.lit = &litPath_;
    q.maxCandidates = maxCandidates;
    q.options = more;
    OccluderUnion u = gatherShadows(tracer, q);
    result_.occluders = u.occluders;
    result_.candidates = u.candidates;
    result_.backFaces = u.backFaces;
    result_.status = u.status == OccluderUnion::Status::TooManyOccluders
                         ? PolygonVisibilityStatus::TooManyOccluders
                     : u.status == OccluderUnion::Status::AlphaTested
                         ? PolygonVisibilityStatus::AlphaTested
                         : PolygonVisibilityStatus::Exact;
    result_.shortcut = u.status == OccluderUnion::Status::Lit       ? VisibilityShortcut::Lit
                       : u.status == OccluderUnion::Status::Covered ? VisibilityShortcut::Covered
                                                                    : VisibilityShortcut::None;
    shadows_ = std::move(u.shadows);
}

double LightShadows::baseV() const {
    SO_CHECK(result_.status == PolygonVisibilityStatus::Exact);
    if (result_.shortcut == VisibilityShortcut::Covered) return 0.0;
    if (shadows_.empty()) return 1.0;
    const double seen = visibleSolidAngle(frame_, p_, n_, litPath_, shadows_);
    return std::clamp(seen / litWhole_, 0.0, 1.0);
}

ClipperLib::Paths LightShadows::visiblePaths() const {
    SO_CHECK(result_.status == PolygonVisibilityStatus::Exact);
    if (result_.shortcut == VisibilityShortcut::Covered) return {};
    if (shadows_.empty()) return {litPath_};
    return lightMinusShadows(litPath_, shadows_);
}

LightShadows::Integrals LightShadows::integrals(const std::vector<dvec3>& region) const {
    Integrals out;
    if (result_.status == PolygonVisibilityStatus::NoLight) return out;
    SO_CHECK(result_.status == PolygonVisibilityStatus::Exact);
    const std::vector<dvec3> lit = clipToHalfSpace(region, {-n_, -glm::dot(n_, p_)});
    if (lit.size() < 3) return out;
    const ClipperLib::Path path = frame_.path(lit);
    // Signed by the path's winding (frame_.path makes it Clipper's positive one), as are the
    // visible parts Clipper returns.
    const double signedWhole = solidAngleOf(frame_, p_, n_, path);
    const double sign = signedWhole < 0.0 ? -1.0 : 1.0;
    out.whole = sign * signedWhole;
    // Covered: the shadows hold the base above the horizon, so every region inside it.
    if (result_.shortcut == VisibilityShortcut::Covered) return out;
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
    out.visible = std::max(0.0, sign * visibleSolidAngle(frame_, p_, n_, path, union_));
    return out;
}

}  // namespace so
