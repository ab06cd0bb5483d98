#include "oracle/exact_sign.h"

#include <atomic>
#include <cmath>
#include <cstdint>
#include <limits>

#include <gmpxx.h>

#include "core/error.h"

namespace so::exact {

namespace {

std::atomic<unsigned long long> gExactEvaluations{0};

// m 2^e, exactly. The scene's coordinates are finite (the loader rejects the rest), so every
// exponent fits; zero keeps e = 0 so that it never forces a long shift.
struct Dyadic {
    mpz_class m;
    long e = 0;
};

Dyadic fromDouble(double x) {
    SO_CHECK(std::isfinite(x));
    Dyadic d;
    if (x == 0.0) return d;
    int exponent = 0;
    const double fraction = std::frexp(x, &exponent);  // x = fraction 2^exponent, 0.5 <= |f| < 1
    d.m = mpz_class(static_cast<long>(std::ldexp(fraction, 53)));  // the 53 bits, exactly
    d.e = long(exponent) - 53;
    return d;
}

Dyadic operator*(const Dyadic& a, const Dyadic& b) {
    Dyadic r;
    r.m = a.m * b.m;
    r.e = sgn(r.m) == 0 ? 0 : a.e + b.e;
    return r;
}

Dyadic operator+(const Dyadic& a, const Dyadic& b) {
    if (sgn(a.m) == 0) return b;
    if (sgn(b.m) == 0) return a;
    Dyadic r;
    if (a.e >= b.e) {
        r.m = (a.m << mp_bitcnt_t(a.e - b.e)) + b.m;
        r.e = b.e;
    } else {
        r.m = a.m + (b.m << mp_bitcnt_t(b.e - a.e));
        r.e = a.e;
    }
    return r;
}

Dyadic operator-(const Dyadic& a) {
    Dyadic r = a;
    r.m = -r.m;
    return r;
}

Dyadic operator-(const Dyadic& a, const Dyadic& b) {
    return a + (-b);
}

struct DVec {
    Dyadic x, y, z;
};

DVec fromVec(const glm::dvec3& v) {
    return {fromDouble(v.x), fromDouble(v.y), fromDouble(v.z)};
}
DVec operator+(const DVec& a, const DVec& b) {
    return {a.x + b.x, a.y + b.y, a.z + b.z};
}
DVec operator-(const DVec& a, const DVec& b) {
    return {a.x - b.x, a.y - b.y, a.z - b.z};
}
DVec cross(const DVec& a, const DVec& b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
Dyadic dot(const DVec& a, const DVec& b) {
    return a.x * b.x + a.y * b.y + a.z * b.z;
}

int sign(const Dyadic& d) {
    return sgn(d.m);
}

// The exact normal (b - a) x (c - a).
DVec exactNormal(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
    const DVec A = fromVec(a);
    ++gExactEvaluations;
    return cross(fromVec(b) - A, fromVec(c) - A);
}

// The double filter for det(e1, e2, e3) where each e_i is a difference of two doubles computed
// with one rounding (or a double taken as is): the determinant computed in double differs from
// the exact one by less than (7 + 56 eps) eps times the permanent of |e_i| (Shewchuk's
// o3derrboundA, eps = 2^-53); we take 8 eps. The bound holds without underflow or overflow, so
// the filter only takes magnitudes in [1e-90, 1e90] (products of three stay normal). Returns 0
// where it cannot decide.
bool inFilterRange(const glm::dvec3& v) {
    for (int i = 0; i < 3; ++i) {
        const double x = std::fabs(v[i]);
        if (x != 0.0 && !(x >= 1e-90 && x <= 1e90)) return false;
    }
    return true;
}

int filteredDeterminant(const glm::dvec3& e1, const glm::dvec3& e2, const glm::dvec3& e3) {
    if (!inFilterRange(e1) || !inFilterRange(e2) || !inFilterRange(e3)) return 0;
    const double c1 = e2.y * e3.z - e2.z * e3.y, c2 = e2.z * e3.x - e2.x * e3.z,
                 c3 = e2.x * e3.y - e2.y * e3.x;
    const double det = e1.x * c1 + e1.y * c2 + e1.z * c3;
    const double permanent = std::fabs(e1.x) * (std::fabs(e2.y * e3.z) + std::fabs(e2.z * e3.y)) +
                             std::fabs(e1.y) * (std::fabs(e2.z * e3.x) + std::fabs(e2.x * e3.z)) +
                             std::fabs(e1.z) * (std::fabs(e2.x * e3.y) + std::fabs(e2.y * e3.x));
    const double bound = 8.0 * std::numeric_limits<double>::epsilon() * 0.5 * permanent;
    if (det > bound) return 1;
    if (det < -bound) return -1;
    return 0;
}

}  // namespace

int orient(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c, const glm::dvec3& q0,
           const glm::dvec3& q1, const glm::dvec3& q2) {
    const bool singleQ = q1 == glm::dvec3(0.0) && q2 == glm::dvec3(0.0);
    if (singleQ) {
        const int s = filteredDeterminant(q0 - a, b - a, c - a);
        if (s != 0) return s;
    }
    const DVec n = exactNormal(a, b, c);
    const DVec q = fromVec(q0) + fromVec(q1) + fromVec(q2);
    return sign(dot(n, q - fromVec(a)));
}

int orientDirection(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c,
                    const glm::dvec3& d) {
    const int s = filteredDeterminant(d, b - a, c - a);
    if (s != 0) return s;
    return sign(dot(exactNormal(a, b, c), fromVec(d)));
}

int sideOfSpan(const glm::dvec3& o, const glm::dvec3& u, const glm::dvec3& v, const glm::dvec3& q) {
    const int s = filteredDeterminant(q - o, u, v);
    if (s != 0) return s;
    ++gExactEvaluations;
    return sign(dot(cross(fromVec(u), fromVec(v)), fromVec(q) - fromVec(o)));
}

int sideOfPlane(const glm::dvec3& o, const glm::dvec3& m, const glm::dvec3& q) {
    ++gExactEvaluations;  // rare (one-sided disk lights at a tie): no filter
    return sign(dot(fromVec(m), fromVec(q) - fromVec(o)));
}

bool diskAbovePlane(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c,
                    const glm::dvec3& o, const glm::dvec3& m, double r) {
    // With N = (b - a) x (c - a), the disk's points are o + r w for unit w perpendicular to m,
    // and the largest N.w over them is |N x m| / |m|. So the highest point is above the plane
    // iff H + r |N x m| / |m| > 0, H = N.(o - a): true if H > 0, else iff r^2 |N x m|^2 >
    // H^2 |m|^2 (both sides squared, H <= 0).
    const DVec n = exactNormal(a, b, c);
    const Dyadic h = dot(n, fromVec(o) - fromVec(a));
    if (sign(h) > 0) return true;
    SO_CHECK(r >= 0.0);
    const DVec mm = fromVec(m);
    const DVec nxm = cross(n, mm);
    const Dyadic r2 = fromDouble(r) * fromDouble(r);
    return sign(r2 * dot(nxm, nxm) - h * h * dot(mm, mm)) > 0;
}

unsigned long long exactEvaluations() {
    return gExactEvaluations.load();
}

}  // namespace so::exact
