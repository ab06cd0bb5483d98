#include "oracle/polygon_visibility.h"

#include <algorithm>
#include <array>
#include <cmath>

#include <glm/geometric.hpp>
#include <polyclipping/clipper.hpp>

#include "oracle/occluder_union.h"
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

// The pyramid from p to the polygon `base` (convex, in the light's plane): a side half-space per
// edge through p, and the light's plane on p's side.
std::vector<ExactTracer::HalfSpace> pyramid(const dvec3& p, const SmallPolygon& base,
                                            const RectLightShape& light) {
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

PolygonVisibility rectLightVisibility(const ExactTracer& tracer, const RectLightShape& light,
                                      const dvec3& p, const dvec3& n, TriangleId self,
                                      uint32_t maxCandidates, const OccluderOptions& more) {
    PolygonVisibility result;
    const double height = glm::dot(light.emitNormal, p - light.corner);  // > 0 on the lit side
    if (!(height > 0.0)) return result;
    // L+: the light above p's horizon.
    const SmallPolygon lit =
        clipToHalfSpace({light.corner, light.corner + light.edgeU,
                         light.corner + light.edgeU + light.edgeV, light.corner + light.edgeV},
                        {-n, -glm::dot(n, p)});
    if (lit.n < 3) return result;
    const LightPlaneFrame frame(light.corner, light.edgeU, light.edgeV, light.emitNormal);
    const ClipperLib::Path litPath = frame.path(lit);
    const double whole = solidAngleOf(frame, p, n, litPath);
    if (!(std::abs(whole) > 0.0)) return result;

    const std::vector<ExactTracer::HalfSpace> planes = pyramid(p, lit, light);
    OccluderQuery q;
    q.p = p;
    q.self = self;
    q.height = height;
    q.pyramid = &planes;
    q.frame = &frame;
    q.lit = &litPath;
    q.maxCandidates = maxCandidates;
    q.options = more;
    const OccluderUnion u = visibleLight(tracer, q);
    result.occluders = u.occluders;
    result.candidates = u.candidates;
    result.backFaces = u.backFaces;
    result.shortcut = u.status == OccluderUnion::Status::Lit       ? VisibilityShortcut::Lit
                      : u.status == OccluderUnion::Status::Covered ? VisibilityShortcut::Covered
                                                                   : VisibilityShortcut::None;
    switch (u.status) {
        case OccluderUnion::Status::TooManyOccluders:
            result.status = PolygonVisibilityStatus::TooManyOccluders;
            return result;
        case OccluderUnion::Status::AlphaTested:
            result.status = PolygonVisibilityStatus::AlphaTested;
            return result;
        case OccluderUnion::Status::Lit:
            result.status = PolygonVisibilityStatus::Exact;
            result.V = 1.0;
            return result;
        case OccluderUnion::Status::Covered:
            result.status = PolygonVisibilityStatus::Exact;
            result.V = 0.0;
            return result;
        case OccluderUnion::Status::Partial:
            break;
    }
    result.status = PolygonVisibilityStatus::Exact;
    double seen = 0.0;
    for (const ClipperLib::Path& path : u.visible) seen += solidAngleOf(frame, p, n, path);
    result.V = std::clamp(seen / whole, 0.0, 1.0);
    return result;
}

}  // namespace so
