// An independent double-precision re-tracer that verifies the Embree oracle ("trace --verify").
// It shares no code with Embree: a plain binary BVH (binned SAH, double-precision boxes) over
// triangles stored in double, a watertight ray/triangle test (Woop, Benthin and Wald 2013) done in
// double with exactly signed edge functions, and exact-as-possible Euclidean distance routines.
//
// Besides the plain closest/any-hit queries it answers the verifier's question for a shadow
// segment: is it occluded, and how far must the segment move before that answer can change (its
// robustness margin)? A disagreement with Embree is only a real one when the margin is larger than
// the precision both tracers work to; see segment().
//
// All distances are Euclidean and in the units of the positions given to the constructor. All
// queries are const and thread-safe.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

namespace so {

// A triangle's identity: mesh index and triangle index within the mesh.
struct TriangleId {
    uint32_t mesh = UINT32_MAX, prim = UINT32_MAX;
    bool operator==(const TriangleId&) const = default;
};

// What an alpha-tested triangle says at a crossing (oracle/exact_alpha.h answers it).
struct AlphaAnswer {
    bool present = true;     // alpha >= cutoff: the crossing counts
    bool ambiguous = false;  // the float path may decide the other way (within its rounding)
};

class ExactTracer {
  public:
    // meshes[i] = {positions (double, already in the frame the caller traces in), indices (3 per
    // triangle), whether its triangles are alpha-tested}.
    struct MeshView {
        const std::vector<glm::dvec3>* positions;
        const std::vector<uint32_t>* indices;
        bool alphaTested = false;
    };
    // The alpha test of alpha-tested meshes, at a crossing of the ray with direction d of
    // triangle id (vertices a, b, c) at barycentrics b1, b2 (of b and c). lsTol: how far, in
    // position units perpendicular to the ray, the float path's ray may pass from this one there.
    class AlphaTest {
      public:
        virtual ~AlphaTest() = default;
        virtual AlphaAnswer at(TriangleId id, const glm::dvec3& a, const glm::dvec3& b,
                               const glm::dvec3& c, double b1, double b2, const glm::dvec3& d,
                               double lsTol) const = 0;
    };
    // Copies what it needs, so the views need not outlive the tracer (`alpha` must). Degenerate
    // (zero-area) triangles are kept but can never be hit; triangles with a non-finite vertex are
    // dropped. Throws std::invalid_argument on an index out of range, an index count not a
    // multiple of 3, or an alpha-tested mesh without `alpha`.
    explicit ExactTracer(const std::vector<MeshView>& meshes, const AlphaTest* alpha = nullptr);
    size_t triangleCount() const { return tris_.size(); }
    // Whether triangle id's mesh is alpha-tested: its crossings count only where alpha passes.
    bool alphaTested(TriangleId id) const {
        return id.mesh < alphaMesh_.size() && alphaMesh_[id.mesh] != 0;
    }

    struct Hit {
        bool found = false;
        double t = 0;
        TriangleId id;
        double b1 = 0, b2 = 0;  // barycentrics of vertex 1 and 2
        // An alpha test at t <= this hit's t (a hole passed through, or the hit itself) was
        // ambiguous: the float path may have seen another surface.
        bool alphaAmbiguous = false;
    };
    // Closest crossing of o + t d (d need not be unit) with t in (tMin, tMax), skipping triangle
    // `skip` and the holes of alpha-tested triangles. A crossing is a point of the closed triangle
    // (edges and vertices included); a ray lying in a triangle's plane never crosses it. Equal t:
    // the smaller (mesh, prim) wins, so the answer does not depend on the BVH. alphaTolAbs +
    // alphaTolPerT * t: the alpha tests' lsTol (AlphaTest) at t.
    Hit closestHit(const glm::dvec3& o, const glm::dvec3& d, double tMin, double tMax,
                   TriangleId skip = {}, double alphaTolAbs = 0.0, double alphaTolPerT = 0.0) const;
    // Any crossing with t in (tMin, tMax), skipping `skip` and alpha holes (decided in double,
    // ambiguity not asked). Faster than closestHit.
    bool occluded(const glm::dvec3& o, const glm::dvec3& d, double tMin, double tMax,
                  TriangleId skip = {}) const;

    // The robustness of the segment S = {o + t d : t in [0, tMax]} (verification).
    //
    // tMax = +inf: S is clipped where the ray leaves the BVH's bounds expanded by tolAbs, or with
    // tolPerT > 0 a little later: where no point of the ray can any longer come within
    // tolAbs + tolPerT * t of the bounds, so no near miss far along is lost. That end is not a
    // real one, so it adds no endpoint term for crossed triangles (below); the clipped tMax is the
    // tMax of everything below. tMax < 0 (or NaN) is taken as 0: S is the point o.
    //
    // For each triangle T other than `skip`, its margin (the distance, in position units, S must
    // move before its answer for T can change) is
    //   S does not cross T:  dist(S, T) = min(dist(S, each edge of T), dist(o, T), dist(end, T));
    //   S crosses T:         min(dist(S, each edge of T), dist(o, T), dist(end, T)), the distance
    //                        to T's boundary, and to the ends (a crossing right at an end is
    //                        fragile);
    // with t_T the parameter on S of that closest approach (in [0, tMax]). Only triangles within
    // reach count: crossed ones and those with margin_T <= tolAbs + tolPerT * tMax. T is ambiguous
    // when margin_T < tolAbs + tolPerT * t_T. Degenerate triangles are never crossed but their
    // edges count (harmless: a zero-area triangle near S can only make the answer more cautious).
    //
    // Alpha-tested triangles: a crossing counts only where the alpha test passes (lsTol at t_hit:
    // tolAbs + tolPerT * t_hit); a crossing of a hole adds no margin (S moving off the triangle
    // or within the hole leaves the answer as it is; a neighbour it could reach has its own
    // margin), and any crossing whose alpha test is ambiguous sets alphaAmbiguous.
    struct SegmentQuery {
        bool occluded = false;   // S crosses some triangle other than `skip` at t in (0, tMax)
        bool ambiguous = false;  // some triangle within reach is ambiguous
        // The triangle with the smallest slack margin_T - (tolAbs + tolPerT * t_T), its margin and
        // t_T (ties: the smaller id). With tolPerT = 0 this is the smallest margin of all; in
        // general ambiguous == (margin < tolAbs + tolPerT * marginT). inf / invalid id when no
        // triangle is within reach.
        double margin = std::numeric_limits<double>::infinity();
        double marginT = 0;  // t of that closest approach
        TriangleId nearest;  // the triangle that set `margin`
        double firstHitT = std::numeric_limits<double>::infinity();  // closest crossing t, or inf
        TriangleId firstHit;
        bool alphaAmbiguous = false;  // some crossing's alpha test was ambiguous
    };
    // tolAbs is in position units, tolPerT in position units per unit of t (so with a unit d, per
    // unit of distance along the segment).
    SegmentQuery segment(const glm::dvec3& o, const glm::dvec3& d, double tMax, TriangleId skip,
                         double tolAbs, double tolPerT) const;

    // A convex region as the intersection of half-spaces {x : dot(normal, x) <= offset}.
    struct HalfSpace {
        glm::dvec3 normal;
        double offset;
    };
    // Calls visit(v0, v1, v2, id) for every triangle that may meet the region, in BVH order:
    // conservative (a node or triangle is left out only when it lies wholly outside one half-space
    // by more than rounding), so the caller clips exactly. visit returns false to stop. Returns
    // false when stopped.
    template <class Visit>
    bool forEachTriangleIn(const std::vector<HalfSpace>& region, Visit&& visit) const;

  private:
    struct Tri {
        glm::dvec3 v0, v1, v2;
        TriangleId id;
    };
    // Interior: children at this + 1 and at `index` (count == 0). Leaf: triangles
    // [index, index + count) of tris_.
    struct Node {
        glm::dvec3 lo, hi;
        uint32_t index = 0, count = 0;
    };
    struct BuildPrim;
    struct RayPre;
    struct SegmentCtx;

    uint32_t build(std::vector<BuildPrim>& prims, const std::vector<Tri>& src, uint32_t begin,
                   uint32_t end, int depth);
    static uint32_t splitSah(std::vector<BuildPrim>& prims, uint32_t begin, uint32_t end);
    static uint32_t splitMedian(std::vector<BuildPrim>& prims, uint32_t begin, uint32_t end);
    template <bool kOrdered, class Upper, class Visit>
    void walk(const RayPre& r, double e, double t0, const Upper& upper, Visit&& visit) const;
    double pad(const glm::dvec3& o, const glm::dvec3& end) const;
    double clipToBounds(const RayPre& r, double tolAbs, double tolPerT) const;
    void segmentLeaf(const Node& leaf, SegmentCtx& ctx, SegmentQuery& q) const;

    AlphaAnswer alphaAt(const Tri& tr, double b1, double b2, const glm::dvec3& d,
                        double lsTol) const;

    std::vector<Tri> tris_;
    std::vector<Node> nodes_;
    std::vector<uint8_t> alphaMesh_;  // per mesh: alpha-tested
    const AlphaTest* alpha_ = nullptr;
    double sceneMaxAbs_ = 0;  // the largest |coordinate| of any vertex
};

template <class Visit>
bool ExactTracer::forEachTriangleIn(const std::vector<HalfSpace>& region, Visit&& visit) const {
    if (nodes_.empty()) return true;
    // Outside a half-space by more than rounding: the smallest dot(normal, x) over the points is
    // above the offset, with a relative margin far above double's error on these magnitudes.
    const auto outside = [&](const HalfSpace& h, double lowest) {
        const double scale =
            std::abs(h.offset) +
            (std::abs(h.normal.x) + std::abs(h.normal.y) + std::abs(h.normal.z)) * sceneMaxAbs_;
        return lowest > h.offset + 1e-9 * scale;
    };
    const auto boxOutside = [&](const Node& node) {
        for (const HalfSpace& h : region) {
            double lowest = 0.0;
            for (int k = 0; k < 3; ++k)
                lowest += h.normal[k] * (h.normal[k] > 0.0 ? node.lo[k] : node.hi[k]);
            if (outside(h, lowest)) return true;
        }
        return false;
    };
    uint32_t stack[128];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
        const Node& node = nodes_[stack[--top]];
        if (boxOutside(node)) continue;
        if (node.count == 0) {
            const uint32_t self = uint32_t(&node - nodes_.data());
            if (top + 2 > 128) throw std::logic_error("ExactTracer: BVH deeper than its stack");
            stack[top++] = node.index;
            stack[top++] = self + 1;
            continue;
        }
        for (uint32_t i = node.index; i < node.index + node.count; ++i) {
            const Tri& t = tris_[i];
            bool cut = false;
            for (const HalfSpace& h : region)
                if (outside(h, std::min({glm::dot(h.normal, t.v0), glm::dot(h.normal, t.v1),
                                         glm::dot(h.normal, t.v2)}))) {
                    cut = true;
                    break;
                }
            if (!cut && !visit(t.v0, t.v1, t.v2, t.id)) return false;
        }
    }
    return true;
}

// The building blocks, exposed so that tests can check them and the BVH against brute force.
namespace exact {

// dist(P, Q) between the segments P = [p0, p1] and Q = [q0, q1] (either may be a point), and
// the parameter s in [0, 1] on P of a closest point.
struct Approach {
    double dist = std::numeric_limits<double>::infinity();
    double s = 0;
};
Approach segmentSegment(const glm::dvec3& p0, const glm::dvec3& p1, const glm::dvec3& q0,
                        const glm::dvec3& q1);
// dist(p, triangle abc), the closed triangle; a degenerate triangle is the union of its edges.
double pointTriangle(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b,
                     const glm::dvec3& c);

// The crossing test of ExactTracer: whether o + t d meets the closed triangle abc at t in
// (tMin, tMax), with t and the barycentrics of b and c.
bool rayTriangle(const glm::dvec3& o, const glm::dvec3& d, double tMin, double tMax,
                 const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c, double& t,
                 double& b1, double& b2);

// ExactTracer::segment()'s per-triangle answer for S = o + t d, t in [0, tMax] (finite):
// whether S crosses abc at t in (0, tMax) and where, and margin_T and t_T as documented there.
// farEndIsReal = false (a clipped infinite segment) drops dist(end, T) for a crossed triangle.
struct SegmentTriangle {
    bool crossed = false;
    double tHit = std::numeric_limits<double>::infinity();
    double margin = std::numeric_limits<double>::infinity();
    double t = 0;
};
SegmentTriangle segmentTriangle(const glm::dvec3& o, const glm::dvec3& d, double tMax,
                                bool farEndIsReal, const glm::dvec3& a, const glm::dvec3& b,
                                const glm::dvec3& c);

}  // namespace exact
}  // namespace so
