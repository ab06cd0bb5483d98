#include "oracle/polygon_visibility.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <polyclipping/clipper.hpp>

namespace so {

namespace {

using glm::dvec3;

// The light's (s, t) in [0, 1] as integers: below Clipper's 2^30 "low range", where its
// arithmetic is plain 64-bit and exact.
constexpr double kQuantum = double(1 << 29);

// Sutherland-Hodgman: the part of the convex or non-convex `poly` where dot(normal, x) <= offset.
std::vector<dvec3> clipToHalfSpace(const std::vector<dvec3>& poly,
                                   const ExactTracer::HalfSpace& h) {
    std::vector<dvec3> out;
    const size_t n = poly.size();
    for (size_t i = 0; i < n; ++i) {
        const dvec3& a = poly[i];
        const dvec3& b = poly[(i + 1) % n];
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
    RectLightShape shape;
    double invUU = 0.0, invVV = 0.0;
    explicit LightFrame(const RectLightShape& l)
        : shape(l),
          invUU(1.0 / glm::dot(l.edgeU, l.edgeU)),
          invVV(1.0 / glm::dot(l.edgeV, l.edgeV)) {}
    ClipperLib::IntPoint quantised(const dvec3& y) const {
        const dvec3 d = y - shape.corner;
        return {ClipperLib::cInt(std::llround(glm::dot(d, shape.edgeU) * invUU * kQuantum)),
                ClipperLib::cInt(std::llround(glm::dot(d, shape.edgeV) * invVV * kQuantum))};
    }
    dvec3 point(const ClipperLib::IntPoint& q) const {
        return shape.corner + (double(q.X) / kQuantum) * shape.edgeU +
               (double(q.Y) / kQuantum) * shape.edgeV;
    }
};

ClipperLib::Path quantisedPath(const LightFrame& frame, const std::vector<dvec3>& poly) {
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
std::vector<ExactTracer::HalfSpace> pyramid(const dvec3& p, const std::vector<dvec3>& base,
                                            const RectLightShape& light) {
    dvec3 centroid(0.0);
    for (const dvec3& b : base) centroid += b;
    centroid /= double(base.size());
    std::vector<ExactTracer::HalfSpace> planes;
    for (size_t i = 0; i < base.size(); ++i) {
        dvec3 m = glm::cross(base[i] - p, base[(i + 1) % base.size()] - p);
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
                                      uint32_t maxCandidates) {
    PolygonVisibility result;
    const double height = glm::dot(light.emitNormal, p - light.corner);  // > 0 on the lit side
    if (!(height > 0.0)) return result;
    // L+: the light above p's horizon.
    const std::vector<dvec3> rect = {light.corner, light.corner + light.edgeU,
                                     light.corner + light.edgeU + light.edgeV,
                                     light.corner + light.edgeV};
    const std::vector<dvec3> lit = clipToHalfSpace(rect, {-n, -glm::dot(n, p)});
    if (lit.size() < 3) return result;
    const LightFrame frame(light);
    const ClipperLib::Path litPath = quantisedPath(frame, lit);
    const double whole = solidAngleOf(frame, p, n, litPath);
    if (!(std::abs(whole) > 0.0)) return result;

    const std::vector<ExactTracer::HalfSpace> planes = pyramid(p, lit, light);
    ClipperLib::Paths shadows;
    bool capped = false;
    tracer.forEachTriangleIn(planes,
                             [&](const dvec3& a, const dvec3& b, const dvec3& c, TriangleId id) {
                                 if (++result.candidates > maxCandidates) {
                                     capped = true;
                                     return false;
                                 }
                                 if (id == self || inPlaneOf(p, a, b, c)) return true;
                                 std::vector<dvec3> part = {a, b, c};
                                 for (const ExactTracer::HalfSpace& h : planes) {
                                     part = clipToHalfSpace(part, h);
                                     if (part.size() < 3) return true;
                                 }
                                 // Central projection through p onto the light's plane: every point
                                 // of the clipped part lies between p and the plane, so
                                 // dot(emitNormal, q - p) is in [-height, 0).
                                 for (dvec3& q : part) {
                                     const double along = glm::dot(light.emitNormal, q - p);
                                     if (!(along < 0.0))
                                         return true;  // at p itself: only a triangle through p
                                     q = p + (q - p) * (-height / along);
                                 }
                                 shadows.push_back(quantisedPath(frame, part));
                                 ++result.occluders;
                                 return true;
                             });
    if (capped) {
        result.status = PolygonVisibilityStatus::TooManyOccluders;
        return result;
    }
    result.status = PolygonVisibilityStatus::Exact;
    if (shadows.empty()) {
        result.V = 1.0;
        return result;
    }
    ClipperLib::Clipper clipper;
    clipper.AddPath(litPath, ClipperLib::ptSubject, true);
    clipper.AddPaths(shadows, ClipperLib::ptClip, true);
    ClipperLib::Paths visible;
    clipper.Execute(ClipperLib::ctDifference, visible, ClipperLib::pftNonZero,
                    ClipperLib::pftNonZero);
    double seen = 0.0;
    for (const ClipperLib::Path& path : visible) seen += solidAngleOf(frame, p, n, path);
    result.V = std::clamp(seen / whole, 0.0, 1.0);
    return result;
}

}  // namespace so
