#include "oracle/exact_tracer.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

#include <glm/geometric.hpp>

namespace so {

using glm::dvec3;

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr uint32_t kLeafSize = 4;
constexpr int kBins = 16;
// Below this depth splits are binned SAH; deeper (pathological input) they are median splits,
// which halve the range, so the depth stays under kMaxSahDepth + 32 and the stack below suffices.
constexpr int kMaxSahDepth = 48;
constexpr int kStackSize = 128;
// Boxes are widened by this much relative to the coordinates involved, so that rounding in the
// triangle and distance tests (a few ulps of those coordinates) can never make the BVH drop a
// triangle that the same test run by brute force would report.
constexpr double kPadRel = 1e-12;

bool idLess(const TriangleId& a, const TriangleId& b) {
    return a.mesh != b.mesh ? a.mesh < b.mesh : a.prim < b.prim;
}

double maxAbs(const dvec3& v) {
    return std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)});
}

bool allFinite(const dvec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// a * b - c * d with the correct sign, and exactly 0 only when the exact value is: the plain
// expression when it is far from 0, else Kahan's difference of products (error <= 2 ulp,
// Jeannerod, Louvet and Muller 2013). The sign is what the watertight test and the degeneracy
// test need.
double diffOfProducts(double a, double b, double c, double d) {
    const double ab = a * b, cd = c * d, p = ab - cd;
    if (std::abs(p) > 1e-15 * (std::abs(ab) + std::abs(cd))) return p;
    const double w = c * d;
    const double e = std::fma(-c, d, w);  // w - c d, exactly
    const double f = std::fma(a, b, -w);
    return f + e;
}

// The cross product, each component correctly signed: zero exactly when a and b are parallel.
dvec3 crossSigned(const dvec3& a, const dvec3& b) {
    return {diffOfProducts(a.y, b.z, a.z, b.y), diffOfProducts(a.z, b.x, a.x, b.z),
            diffOfProducts(a.x, b.y, a.y, b.x)};
}

// The end of the segment o + t d, t in [0, tEnd]; one function so every caller gets the same bits.
dvec3 segmentEnd(const dvec3& o, const dvec3& d, double tEnd) {
    return o + tEnd * d;
}

// Woop, Benthin and Wald's shear: the ray becomes the +z axis of a sheared frame.
struct Shear {
    bool valid = false;
    int kx = 0, ky = 1, kz = 2;
    double sx = 0, sy = 0;
};

Shear makeShear(const dvec3& d) {
    Shear s;
    if (!allFinite(d)) return s;
    const dvec3 ad = glm::abs(d);
    s.kz = ad.x >= ad.y ? (ad.x >= ad.z ? 0 : 2) : (ad.y >= ad.z ? 1 : 2);
    s.kx = (s.kz + 1) % 3;
    s.ky = (s.kx + 1) % 3;
    if (d[s.kz] < 0) std::swap(s.kx, s.ky);  // keeps the winding, so U, V, W keep their meaning
    s.sx = d[s.kx] / d[s.kz];
    s.sy = d[s.ky] / d[s.kz];
    s.valid = d[s.kz] != 0;
    return s;
}

// Whether o + t d meets the closed triangle abc at t in (tMin, tMax). Watertight: the edge
// functions are correctly signed for the sheared vertices, and a shared edge is computed from the
// same sheared values in both of its triangles, so a ray cannot slip between two of them. A
// degenerate triangle or a ray in the triangle's plane (d . n == 0) never crosses.
bool crossTriangle(const Shear& sh, const dvec3& o, const dvec3& d, const dvec3& a, const dvec3& b,
                   const dvec3& c, double tMin, double tMax, double& t, double& b1, double& b2) {
    const dvec3 A = a - o, B = b - o, C = c - o;
    const double ax = A[sh.kx] - sh.sx * A[sh.kz], ay = A[sh.ky] - sh.sy * A[sh.kz];
    const double bx = B[sh.kx] - sh.sx * B[sh.kz], by = B[sh.ky] - sh.sy * B[sh.kz];
    const double cx = C[sh.kx] - sh.sx * C[sh.kz], cy = C[sh.ky] - sh.sy * C[sh.kz];
    const double u = diffOfProducts(cx, by, cy, bx);
    const double v = diffOfProducts(ax, cy, ay, cx);
    const double w = diffOfProducts(bx, ay, by, ax);
    if ((u < 0 || v < 0 || w < 0) && (u > 0 || v > 0 || w > 0)) return false;
    const double det = u + v + w;
    if (det == 0) return false;
    // t from the plane rather than from the sheared z: exact for axis-aligned planes (a shadow
    // ray leaving a floor gets t = 0 exactly, not a few ulps either side), as accurate otherwise.
    // Computed only for candidate hits, as is the plane test.
    const dvec3 n = crossSigned(b - a, c - a);
    const double dn = glm::dot(d, n);
    if (dn == 0) return false;
    const double tt = glm::dot(A, n) / dn;
    if (!(tt > tMin && tt < tMax)) return false;
    t = tt;
    b1 = v / det;
    b2 = w / det;
    return true;
}

// dist(p, segment [a, b]) and the parameter on [a, b] of the closest point. The difference is
// formed from the nearer end so that the error scales with the local geometry, not with the
// coordinates' magnitude.
exact::Approach pointSegment(const dvec3& p, const dvec3& a, const dvec3& b) {
    const dvec3 ab = b - a, ap = p - a;
    const double len2 = glm::dot(ab, ab);
    double s = 0;
    if (len2 > 0) s = std::clamp(glm::dot(ap, ab) / len2, 0.0, 1.0);
    const dvec3 diff = s <= 0.5 ? ap - s * ab : (p - b) + (1.0 - s) * ab;
    return {glm::length(diff), s};
}

// min over triangle abc's edges and over the segment's ends of the distances to S = [o, end]
// (end only if withEnd), with the parameter t on S (in [0, tEnd]) of that closest approach.
void triangleMargin(const dvec3& o, const dvec3& end, double tEnd, bool withEnd, const dvec3& a,
                    const dvec3& b, const dvec3& c, double& margin, double& t) {
    margin = kInf;
    t = 0;
    const auto take = [&](double dist, double tt) {
        if (dist < margin) margin = dist, t = tt;
    };
    const std::array<std::pair<const dvec3*, const dvec3*>, 3> edges{
        {{&a, &b}, {&b, &c}, {&c, &a}}};
    for (const auto& [e0, e1] : edges) {
        const exact::Approach ap = exact::segmentSegment(o, end, *e0, *e1);
        take(ap.dist, ap.s >= 1 ? tEnd : ap.s * tEnd);
    }
    take(exact::pointTriangle(o, a, b, c), 0.0);
    if (withEnd) take(exact::pointTriangle(end, a, b, c), tEnd);
}

struct Box {
    dvec3 lo{kInf}, hi{-kInf};
    void grow(const dvec3& p) { lo = glm::min(lo, p), hi = glm::max(hi, p); }
    void grow(const Box& b) { lo = glm::min(lo, b.lo), hi = glm::max(hi, b.hi); }
    double halfArea() const {
        const dvec3 e = hi - lo;
        return e.x * e.y + e.y * e.z + e.z * e.x;
    }
};

int longestAxis(const dvec3& extent) {
    return extent.x >= extent.y ? (extent.x >= extent.z ? 0 : 2) : (extent.y >= extent.z ? 1 : 2);
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// Exposed building blocks

namespace exact {

Approach segmentSegment(const dvec3& p0, const dvec3& p1, const dvec3& q0, const dvec3& q1) {
    // The minimum of a convex function over [0,1]^2: on the square's boundary (a point against a
    // segment, four cases, each robust) or at the interior critical point of the two lines.
    Approach best = pointSegment(p0, q0, q1);
    best.s = 0;
    Approach c = pointSegment(p1, q0, q1);
    if (c.dist < best.dist) best = {c.dist, 1.0};
    c = pointSegment(q0, p0, p1);
    if (c.dist < best.dist) best = c;
    c = pointSegment(q1, p0, p1);
    if (c.dist < best.dist) best = c;
    // Interior: with n = u x v and w = q0 - p0, the closest points of the lines are at
    // s = ((w x v) . n) / |n|^2 and t = ((w x u) . n) / |n|^2 (better conditioned than the normal
    // equations when the segments are nearly parallel), and the lines' distance is |w . n| / |n|.
    // Where near-parallel segments make s, t inaccurate that distance is still a lower bound, so
    // the margin errs on the cautious side.
    const dvec3 u = p1 - p0, v = q1 - q0, w = q0 - p0;
    const dvec3 n = glm::cross(u, v);
    const double nn = glm::dot(n, n);
    if (nn > 0 && std::isfinite(nn)) {
        const double s = glm::dot(glm::cross(w, v), n) / nn;
        const double t = glm::dot(glm::cross(w, u), n) / nn;
        if (s > 0 && s < 1 && t > 0 && t < 1) {
            const double dist = std::abs(glm::dot(w, n)) / std::sqrt(nn);
            if (dist < best.dist) best = {dist, s};
        }
    }
    return best;
}

double pointTriangle(const dvec3& p, const dvec3& a, const dvec3& b, const dvec3& c) {
    // If p projects inside the triangle the distance is to its plane, else to its boundary.
    const dvec3 n = crossSigned(b - a, c - a);
    if (n != dvec3(0.0)) {
        const bool inside = glm::dot(glm::cross(b - a, p - a), n) >= 0 &&
                            glm::dot(glm::cross(c - b, p - b), n) >= 0 &&
                            glm::dot(glm::cross(a - c, p - c), n) >= 0;
        if (inside) return std::abs(glm::dot(p - a, n)) / glm::length(n);
    }
    return std::min(
        {pointSegment(p, a, b).dist, pointSegment(p, b, c).dist, pointSegment(p, c, a).dist});
}

bool rayTriangle(const dvec3& o, const dvec3& d, double tMin, double tMax, const dvec3& a,
                 const dvec3& b, const dvec3& c, double& t, double& b1, double& b2) {
    const Shear sh = makeShear(d);
    return sh.valid && allFinite(o) && crossTriangle(sh, o, d, a, b, c, tMin, tMax, t, b1, b2);
}

SegmentTriangle segmentTriangle(const dvec3& o, const dvec3& d, double tMax, bool farEndIsReal,
                                const dvec3& a, const dvec3& b, const dvec3& c) {
    SegmentTriangle r;
    const double tEnd = std::max(0.0, tMax);
    const Shear sh = makeShear(d);
    double b1, b2;
    r.crossed = sh.valid && crossTriangle(sh, o, d, a, b, c, 0.0, tEnd, r.tHit, b1, b2);
    if (!r.crossed) r.tHit = kInf;
    triangleMargin(o, segmentEnd(o, d, tEnd), tEnd, !r.crossed || farEndIsReal, a, b, c, r.margin,
                   r.t);
    return r;
}

}  // namespace exact

// ---------------------------------------------------------------------------------------------
// ExactTracer

// A ray prepared for the slab test and the triangle test.
struct ExactTracer::RayPre {
    enum Axis : uint8_t { Regular, Parallel, Tiny };
    dvec3 o, d, inv;
    std::array<Axis, 3> axis{};
    Shear shear;
    bool valid = false;  // o and d finite, d != 0

    RayPre(const dvec3& org, const dvec3& dir) : o(org), d(dir) {
        for (int i = 0; i < 3; ++i) {
            inv[i] = 1.0 / d[i];
            // d_i == 0: (lo - o_i) * inf could be 0 * inf = NaN, so test the slab directly.
            // 1 / d_i overflowing: divide instead, which cannot produce NaN.
            axis[i] = d[i] == 0 ? Parallel : std::isfinite(inv[i]) ? Regular : Tiny;
        }
        shear = makeShear(d);
        valid = allFinite(o) && allFinite(d) && d != dvec3(0.0);
    }
};

struct ExactTracer::BuildPrim {
    Box box;
    dvec3 centroid;
    uint32_t tri = 0;
};

struct ExactTracer::SegmentCtx {
    const RayPre& ray;
    dvec3 end;
    double tEnd;
    bool farEndIsReal;
    double tolAbs, tolPerT, reach;
    TriangleId skip;
    const RayPre& walkRay;  // the ray the boxes are tested with (d = 0 when `ray` is invalid)
    double expand;          // how far boxes are widened: reach and the padding
    double bestSlack = kInf;
};

namespace {

// Whether the ray meets the box [lo - e, hi + e] at some t in [t0, t1]; tNear gets the entry t.
template <class Ray>
bool slab(const dvec3& lo, const dvec3& hi, const Ray& r, double e, double t0, double t1,
          double& tNear) {
    for (int i = 0; i < 3; ++i) {
        const double l = lo[i] - e, h = hi[i] + e;
        double a, b;
        switch (r.axis[i]) {
            case Ray::Parallel:
                if (r.o[i] < l || r.o[i] > h) return false;
                continue;
            case Ray::Regular:
                a = (l - r.o[i]) * r.inv[i], b = (h - r.o[i]) * r.inv[i];
                break;
            default:
                a = (l - r.o[i]) / r.d[i], b = (h - r.o[i]) / r.d[i];
                break;
        }
        if (a > b) std::swap(a, b);
        t0 = std::max(t0, a);
        t1 = std::min(t1, b);
        if (t0 > t1) return false;
    }
    tNear = t0;
    return true;
}

}  // namespace

ExactTracer::ExactTracer(const std::vector<MeshView>& meshes, const AlphaTest* alpha)
    : alpha_(alpha) {
    std::vector<Tri> src;
    for (size_t m = 0; m < meshes.size(); ++m) {
        const MeshView& mv = meshes[m];
        if (!mv.positions || !mv.indices)
            throw std::invalid_argument("ExactTracer: mesh " + std::to_string(m) + " is null");
        if (mv.alphaTested && !alpha)
            throw std::invalid_argument("ExactTracer: mesh " + std::to_string(m) +
                                        " is alpha-tested but no alpha test was given");
        alphaMesh_.push_back(mv.alphaTested ? 1 : 0);
        const std::vector<glm::dvec3>& pos = *mv.positions;
        const std::vector<uint32_t>& idx = *mv.indices;
        if (idx.size() % 3 != 0)
            throw std::invalid_argument("ExactTracer: mesh " + std::to_string(m) +
                                        ": index count not a multiple of 3");
        for (size_t p = 0; p < idx.size() / 3; ++p) {
            const uint32_t i0 = idx[3 * p], i1 = idx[3 * p + 1], i2 = idx[3 * p + 2];
            if (i0 >= pos.size() || i1 >= pos.size() || i2 >= pos.size())
                throw std::invalid_argument("ExactTracer: mesh " + std::to_string(m) +
                                            ": index out of range");
            const Tri t{
                pos[i0], pos[i1], pos[i2], {static_cast<uint32_t>(m), static_cast<uint32_t>(p)}};
            if (allFinite(t.v0) && allFinite(t.v1) && allFinite(t.v2)) src.push_back(t);
        }
    }
    if (src.empty()) return;

    std::vector<BuildPrim> prims(src.size());
    for (size_t i = 0; i < src.size(); ++i) {
        BuildPrim& p = prims[i];
        p.box.grow(src[i].v0), p.box.grow(src[i].v1), p.box.grow(src[i].v2);
        p.centroid = 0.5 * (p.box.lo + p.box.hi);
        p.tri = static_cast<uint32_t>(i);
    }
    nodes_.reserve(src.size() / 2 + 1);
    tris_.reserve(src.size());
    build(prims, src, 0, static_cast<uint32_t>(prims.size()), 0);
    nodes_.shrink_to_fit();
    sceneMaxAbs_ = std::max(maxAbs(nodes_[0].lo), maxAbs(nodes_[0].hi));
}

uint32_t ExactTracer::build(std::vector<BuildPrim>& prims, const std::vector<Tri>& src,
                            uint32_t begin, uint32_t end, int depth) {
    const uint32_t self = static_cast<uint32_t>(nodes_.size());
    nodes_.emplace_back();
    Box box;
    for (uint32_t i = begin; i < end; ++i) box.grow(prims[i].box);
    nodes_[self].lo = box.lo;
    nodes_[self].hi = box.hi;
    if (end - begin <= kLeafSize) {
        nodes_[self].index = static_cast<uint32_t>(tris_.size());
        nodes_[self].count = end - begin;
        for (uint32_t i = begin; i < end; ++i) tris_.push_back(src[prims[i].tri]);
        return self;
    }
    uint32_t mid = depth < kMaxSahDepth ? splitSah(prims, begin, end) : begin;
    if (mid == begin || mid == end) mid = splitMedian(prims, begin, end);
    build(prims, src, begin, mid, depth + 1);  // lands at self + 1
    const uint32_t right = build(prims, src, mid, end, depth + 1);
    nodes_[self].index = right;
    return self;
}

uint32_t ExactTracer::splitMedian(std::vector<BuildPrim>& prims, uint32_t begin, uint32_t end) {
    Box cb;
    for (uint32_t i = begin; i < end; ++i) cb.grow(prims[i].centroid);
    const int axis = longestAxis(cb.hi - cb.lo);
    const uint32_t mid = begin + (end - begin) / 2;
    // Ties broken by the triangle's input position, so the tree is the same on every platform.
    std::nth_element(prims.begin() + begin, prims.begin() + mid, prims.begin() + end,
                     [axis](const BuildPrim& a, const BuildPrim& b) {
                         return a.centroid[axis] != b.centroid[axis]
                                    ? a.centroid[axis] < b.centroid[axis]
                                    : a.tri < b.tri;
                     });
    return mid;
}

// Binned SAH along the longest axis of the centroids' bounds; returns the split position, or
// `begin` when the centroids coincide (the caller then splits at the median).
uint32_t ExactTracer::splitSah(std::vector<BuildPrim>& prims, uint32_t begin, uint32_t end) {
    Box cb;
    for (uint32_t i = begin; i < end; ++i) cb.grow(prims[i].centroid);
    const int axis = longestAxis(cb.hi - cb.lo);
    const double lo = cb.lo[axis], extent = cb.hi[axis] - cb.lo[axis];
    if (!(extent > 0) || !std::isfinite(extent)) return begin;
    const double scale = kBins / extent;
    const auto binOf = [&](const BuildPrim& p) {
        return std::min(kBins - 1, static_cast<int>((p.centroid[axis] - lo) * scale));
    };
    std::array<Box, kBins> boxes;
    std::array<uint32_t, kBins> counts{};
    for (uint32_t i = begin; i < end; ++i) {
        const int b = binOf(prims[i]);
        boxes[b].grow(prims[i].box);
        ++counts[b];
    }
    // rightCost[k]: the cost of bins k + 1 .. kBins - 1 as one child.
    std::array<double, kBins> rightCost{};
    Box acc;
    uint32_t n = 0;
    for (int k = kBins - 1; k > 0; --k) {
        acc.grow(boxes[k]), n += counts[k];
        rightCost[k - 1] = n > 0 ? acc.halfArea() * n : kInf;
    }
    acc = Box();
    n = 0;
    int best = -1;
    double bestCost = kInf;
    for (int k = 0; k < kBins - 1; ++k) {
        acc.grow(boxes[k]), n += counts[k];
        if (n == 0) continue;
        const double cost = acc.halfArea() * n + rightCost[k];
        if (cost < bestCost) bestCost = cost, best = k;
    }
    if (best < 0) return begin;
    const auto it = std::partition(prims.begin() + begin, prims.begin() + end,
                                   [&](const BuildPrim& p) { return binOf(p) <= best; });
    return static_cast<uint32_t>(it - prims.begin());
}

// Visits the leaves whose boxes, widened by e, meet the ray at t in [t0, upper()], nearest box
// first when kOrdered. visit(leaf) returns false to stop. upper() may shrink as leaves are visited.
template <bool kOrdered, class Upper, class Visit>
void ExactTracer::walk(const RayPre& r, double e, double t0, const Upper& upper,
                       Visit&& visit) const {
    struct Entry {
        uint32_t node;
        double tNear;
    };
    std::array<Entry, kStackSize> stack;
    int sp = 0;
    double tn = 0;
    if (!slab(nodes_[0].lo, nodes_[0].hi, r, e, t0, upper(), tn)) return;
    stack[sp++] = {0, tn};
    while (sp > 0) {
        const Entry en = stack[--sp];
        if (en.tNear > upper()) continue;
        const Node& node = nodes_[en.node];
        if (node.count > 0) {
            if (!visit(node)) return;
            continue;
        }
        uint32_t a = en.node + 1, b = node.index;
        double ta = 0, tb = 0;
        bool ha = slab(nodes_[a].lo, nodes_[a].hi, r, e, t0, upper(), ta);
        bool hb = slab(nodes_[b].lo, nodes_[b].hi, r, e, t0, upper(), tb);
        if (kOrdered && ha && hb && tb < ta) std::swap(a, b), std::swap(ta, tb);
        if (hb) stack[sp++] = {b, tb};  // the far child first, so the near one pops first
        if (ha) stack[sp++] = {a, ta};
    }
}

double ExactTracer::pad(const dvec3& o, const dvec3& end) const {
    const double m = std::max(maxAbs(o), allFinite(end) ? maxAbs(end) : 0.0);
    return kPadRel * (m + sceneMaxAbs_) + std::numeric_limits<double>::min();
}

AlphaAnswer ExactTracer::alphaAt(const Tri& tr, double b1, double b2, const dvec3& d,
                                 double lsTol) const {
    if (!alphaTested(tr.id)) return {};
    return alpha_->at(tr.id, tr.v0, tr.v1, tr.v2, b1, b2, d, lsTol);
}

ExactTracer::Hit ExactTracer::closestHit(const dvec3& o, const dvec3& d, double tMin, double tMax,
                                         TriangleId skip, double alphaTolAbs,
                                         double alphaTolPerT) const {
    Hit hit;
    const RayPre r(o, d);
    if (nodes_.empty() || !r.valid || !r.shear.valid || !(tMax > tMin)) return hit;
    double upper = tMax;       // t < upper; after a hit, t <= hit.t (equal t: the smaller id wins)
    double ambiguousT = kInf;  // the nearest crossing whose alpha test was ambiguous
    const auto visit = [&](const Node& leaf) {
        for (uint32_t i = leaf.index; i < leaf.index + leaf.count; ++i) {
            const Tri& tr = tris_[i];
            double t, b1, b2;
            if (tr.id == skip ||
                !crossTriangle(r.shear, o, d, tr.v0, tr.v1, tr.v2, tMin, upper, t, b1, b2))
                continue;
            const AlphaAnswer a = alphaAt(tr, b1, b2, d, alphaTolAbs + alphaTolPerT * t);
            if (a.ambiguous) ambiguousT = std::min(ambiguousT, t);
            if (!a.present) continue;  // a hole: the ray goes on
            if (hit.found && t == hit.t && !idLess(tr.id, hit.id)) continue;
            hit = {true, t, tr.id, b1, b2, false};
            upper = std::nextafter(t, kInf);
        }
        return true;
    };
    const auto bound = [&] { return hit.found ? hit.t : tMax; };
    walk<true>(r, pad(o, o), tMin, bound, visit);
    hit.alphaAmbiguous = ambiguousT <= (hit.found ? hit.t : tMax);
    return hit;
}

bool ExactTracer::occluded(const dvec3& o, const dvec3& d, double tMin, double tMax,
                           TriangleId skip) const {
    const RayPre r(o, d);
    if (nodes_.empty() || !r.valid || !r.shear.valid || !(tMax > tMin)) return false;
    bool found = false;
    const auto visit = [&](const Node& leaf) {
        for (uint32_t i = leaf.index; i < leaf.index + leaf.count; ++i) {
            const Tri& tr = tris_[i];
            double t, b1, b2;
            if (tr.id != skip &&
                crossTriangle(r.shear, o, d, tr.v0, tr.v1, tr.v2, tMin, tMax, t, b1, b2) &&
                alphaAt(tr, b1, b2, d, 0.0).present) {
                found = true;
                return false;
            }
        }
        return true;
    };
    const auto bound = [&] { return tMax; };
    walk<false>(r, pad(o, o), tMin, bound, visit);
    return found;
}

// The end of an infinite segment: past it no point of the ray is within tolAbs + tolPerT * t of
// the scene's bounds B, so nothing beyond can be in reach. Along each axis j with |d_j| > tolPerT,
// once the ray has crossed B's far plane at tau_j, dist(o + t d, B) >= (t - tau_j) |d_j|, which
// stays below tolAbs + tolPerT t only while t < (tolAbs + tau_j |d_j|) / (|d_j| - tolPerT). With
// tolPerT = 0 that is where the ray leaves B widened by tolAbs.
double ExactTracer::clipToBounds(const RayPre& r, double tolAbs, double tolPerT) const {
    double tEnd = kInf;
    for (int i = 0; i < 3; ++i) {
        const double ad = std::abs(r.d[i]);
        if (!(ad > tolPerT)) continue;
        const double plane = r.d[i] > 0 ? nodes_[0].hi[i] : nodes_[0].lo[i];
        const double tau = (plane - r.o[i]) / r.d[i];
        tEnd = std::min(tEnd, (tolAbs + tau * ad) / (ad - tolPerT));
    }
    // No axis qualifies only when tolPerT >= |d|_inf, a tolerance too large to mean anything:
    // fall back to the farthest corner.
    if (tEnd == kInf) {
        const dvec3 far = glm::max(glm::abs(nodes_[0].lo - r.o), glm::abs(nodes_[0].hi - r.o));
        tEnd = (glm::length(far) + tolAbs) / glm::length(r.d);
    }
    return std::max(0.0, tEnd);
}

void ExactTracer::segmentLeaf(const Node& leaf, SegmentCtx& ctx, SegmentQuery& q) const {
    const RayPre& r = ctx.ray;
    for (uint32_t i = leaf.index; i < leaf.index + leaf.count; ++i) {
        const Tri& tr = tris_[i];
        if (tr.id == ctx.skip) continue;
        double tHit = kInf, b1, b2;
        const bool crossed = r.shear.valid && crossTriangle(r.shear, r.o, r.d, tr.v0, tr.v1, tr.v2,
                                                            0.0, ctx.tEnd, tHit, b1, b2);
        if (crossed && alphaTested(tr.id)) {
            const AlphaAnswer a = alphaAt(tr, b1, b2, r.d, ctx.tolAbs + ctx.tolPerT * tHit);
            q.alphaAmbiguous = q.alphaAmbiguous || a.ambiguous;
            if (!a.present) continue;  // through a hole: no occlusion, no margin (header)
        }
        if (crossed && (tHit < q.firstHitT || (tHit == q.firstHitT && idLess(tr.id, q.firstHit))))
            q.firstHitT = tHit, q.firstHit = tr.id;
        if (!crossed) {
            // Cheap rejection of what is certainly out of reach: the test the BVH's boxes get,
            // on the triangle's own box (widened by the padding too, so it never drops a
            // triangle the distance test would keep).
            Box tb;
            tb.grow(tr.v0), tb.grow(tr.v1), tb.grow(tr.v2);
            double tNear;
            if (!slab(tb.lo, tb.hi, ctx.walkRay, ctx.expand, 0.0, ctx.tEnd, tNear)) continue;
        }
        double margin, tT;
        triangleMargin(r.o, ctx.end, ctx.tEnd, !crossed || ctx.farEndIsReal, tr.v0, tr.v1, tr.v2,
                       margin, tT);
        if (!crossed && margin > ctx.reach) continue;
        const double slack = margin - (ctx.tolAbs + ctx.tolPerT * tT);
        if (slack < 0) q.ambiguous = true;
        if (slack < ctx.bestSlack || (slack == ctx.bestSlack && idLess(tr.id, q.nearest))) {
            ctx.bestSlack = slack;
            q.margin = margin, q.marginT = tT, q.nearest = tr.id;
        }
    }
}

ExactTracer::SegmentQuery ExactTracer::segment(const dvec3& o, const dvec3& d, double tMax,
                                               TriangleId skip, double tolAbs,
                                               double tolPerT) const {
    SegmentQuery q;
    const RayPre r(o, d);
    if (nodes_.empty() || !allFinite(o)) return q;
    tolAbs = std::isfinite(tolAbs) ? std::max(0.0, tolAbs) : 0.0;
    tolPerT = std::isfinite(tolPerT) ? std::max(0.0, tolPerT) : 0.0;
    const bool farEndIsReal = tMax != kInf || !r.valid;
    double tEnd = 0;
    if (r.valid)
        tEnd = farEndIsReal ? std::max(0.0, tMax) : clipToBounds(r, tolAbs + pad(o, o), tolPerT);
    if (std::isnan(tEnd)) return q;

    const dvec3 end = r.valid ? segmentEnd(o, d, tEnd) : o;
    const double reach = tolAbs + tolPerT * tEnd;
    const double e = reach + pad(o, end);
    // A zero or non-finite d leaves S = {o}: every axis is then tested as parallel.
    const RayPre point(o, dvec3(0.0));
    const RayPre& walkRay = r.valid ? r : point;
    SegmentCtx ctx{r, end, tEnd, farEndIsReal, tolAbs, tolPerT, reach, skip, walkRay, e};
    const auto visit = [&](const Node& leaf) {
        segmentLeaf(leaf, ctx, q);
        return true;
    };
    const auto bound = [&] { return tEnd; };
    walk<false>(walkRay, e, 0.0, bound, visit);
    q.occluded = q.firstHitT < kInf;
    return q;
}

}  // namespace so
