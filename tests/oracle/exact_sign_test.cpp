// oracle/exact_sign.h against an independent reference (GMP rationals, mpq_class, straight from
// the definitions), on the inputs where double arithmetic fails: exactly coplanar dyadic points,
// points one ulp off the plane, wide ranges of magnitude, and a disk tangent to a plane.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <random>

#include <gmpxx.h>
#include <gtest/gtest.h>

#include "oracle/exact_sign.h"

namespace so {
namespace {

using glm::dvec3;

mpq_class q(double x) {
    return mpq_class(x);  // exact: every double is a rational
}

struct QVec {
    mpq_class x, y, z;
};
QVec qv(const dvec3& v) {
    return {q(v.x), q(v.y), q(v.z)};
}
QVec sub(const QVec& a, const QVec& b) {
    return {a.x - b.x, a.y - b.y, a.z - b.z};
}
QVec cross(const QVec& a, const QVec& b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
mpq_class dot(const QVec& a, const QVec& b) {
    return a.x * b.x + a.y * b.y + a.z * b.z;
}

int refOrient(const dvec3& a, const dvec3& b, const dvec3& c, const dvec3& p) {
    const QVec A = qv(a);
    return sgn(dot(cross(sub(qv(b), A), sub(qv(c), A)), sub(qv(p), A)));
}

// Doubles of mixed magnitude: mantissa random, exponent in [-e, e].
struct Gen {
    std::mt19937_64 rng{20261123};
    double number(int e) {
        std::uniform_real_distribution<double> m(-1.0, 1.0);
        std::uniform_int_distribution<int> x(-e, e);
        return std::ldexp(m(rng), x(rng));
    }
    dvec3 vec(int e) { return {number(e), number(e), number(e)}; }
    int64_t integer(int64_t n) { return std::uniform_int_distribution<int64_t>(-n, n)(rng); }
};

// Points on the plane of (a, b, c) built exactly: a + s (b - a) + t (c - a) with small dyadic s, t
// and integer vertices, so that every coordinate is a double computed without rounding.
TEST(ExactSign, CoplanarPointsAreZeroAndOneUlpOffIsNot) {
    Gen g;
    int checked = 0;
    for (int i = 0; i < 2000; ++i) {
        const dvec3 a(g.integer(1 << 20), g.integer(1 << 20), g.integer(1 << 20));
        const dvec3 b = a + dvec3(g.integer(1 << 10), g.integer(1 << 10), g.integer(1 << 10));
        const dvec3 c = a + dvec3(g.integer(1 << 10), g.integer(1 << 10), g.integer(1 << 10));
        const double s = std::ldexp(double(g.integer(1 << 12)), -6);
        const double t = std::ldexp(double(g.integer(1 << 12)), -6);
        const dvec3 p = a + s * (b - a) + t * (c - a);
        if (refOrient(a, b, c, p) != 0) continue;  // a rounding made it off the plane: skip
        ++checked;
        EXPECT_EQ(exact::orient(a, b, c, p), 0);
        for (int k = 0; k < 3; ++k)
            for (double dir : {-1.0, 1.0}) {
                dvec3 off = p;
                off[k] = std::nextafter(off[k], dir * INFINITY);
                ASSERT_EQ(exact::orient(a, b, c, off), refOrient(a, b, c, off)) << i;
            }
        // The same plane seen through a direction in it: (b - a) is, exactly.
        EXPECT_EQ(exact::orientDirection(a, b, c, b - a), 0);
    }
    EXPECT_GT(checked, 1500);
}

TEST(ExactSign, AgreesWithRationalsOnWideMagnitudes) {
    Gen g;
    const unsigned long long before = exact::exactEvaluations();
    for (int i = 0; i < 20000; ++i) {
        const int e = i % 3 == 0 ? 60 : 8;
        const dvec3 a = g.vec(e), b = g.vec(e), c = g.vec(e), p = g.vec(e), d = g.vec(e);
        ASSERT_EQ(exact::orient(a, b, c, p), refOrient(a, b, c, p)) << i;
        const QVec n = cross(sub(qv(b), qv(a)), sub(qv(c), qv(a)));
        ASSERT_EQ(exact::orientDirection(a, b, c, d), sgn(dot(n, qv(d)))) << i;
        ASSERT_EQ(exact::sideOfSpan(a, b, c, p), sgn(dot(cross(qv(b), qv(c)), sub(qv(p), qv(a)))))
            << i;
        ASSERT_EQ(exact::sideOfPlane(a, b, p), sgn(dot(qv(b), sub(qv(p), qv(a))))) << i;
        // The exact sum of three terms (a rect corner).
        const QVec sum = {q(p.x) + q(d.x) + q(c.x), q(p.y) + q(d.y) + q(c.y),
                          q(p.z) + q(d.z) + q(c.z)};
        ASSERT_EQ(exact::orient(a, b, c, p, d, c), sgn(dot(n, sub(sum, qv(a))))) << i;
    }
    // The double filter decides almost all of the 60,000 filtered calls (orient with one term,
    // orientDirection, sideOfSpan); orient with three terms and sideOfPlane (40,000) always run
    // exactly.
    const unsigned long long fallbacks = exact::exactEvaluations() - before - 40000u;
    std::printf("[ exact ] %llu of 60000 filtered calls fell back to exact arithmetic\n",
                fallbacks);
    EXPECT_LT(fallbacks, 600u);
}

TEST(ExactSign, SwappingTwoVerticesFlipsTheSign) {
    Gen g;
    for (int i = 0; i < 1000; ++i) {
        const dvec3 a = g.vec(4), b = g.vec(4), c = g.vec(4), p = g.vec(4);
        EXPECT_EQ(exact::orient(a, b, c, p), -exact::orient(a, c, b, p));
        EXPECT_EQ(exact::orient(a, b, c, p), exact::orient(b, c, a, p));
    }
}

// The plane z = 0 (normal +z) and a disk below it by h, its normal (0, 3, 4): its highest point is
// -h + r * 3/5 above the plane, exactly 0 for h = 3, r = 5.
TEST(ExactSign, DiskTangentToThePlaneIsNotAbove) {
    const dvec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0), m(0, 3, 4);
    const double h = 3.0, r = 5.0;
    EXPECT_FALSE(exact::diskAbovePlane(a, b, c, {7, -2, -h}, m, r));
    EXPECT_TRUE(exact::diskAbovePlane(a, b, c, {7, -2, std::nextafter(-h, 0.0)}, m, r));
    EXPECT_FALSE(exact::diskAbovePlane(a, b, c, {7, -2, std::nextafter(-h, -INFINITY)}, m, r));
    EXPECT_TRUE(exact::diskAbovePlane(a, b, c, {7, -2, -h}, m, std::nextafter(r, INFINITY)));
    // In the plane: above unless its normal is parallel to the plane's.
    EXPECT_FALSE(exact::diskAbovePlane(a, b, c, {1, 1, 0}, {0, 0, 2}, r));
    EXPECT_FALSE(exact::diskAbovePlane(a, b, c, {1, 1, 0}, {0, 0, -1}, r));
    EXPECT_TRUE(exact::diskAbovePlane(a, b, c, {1, 1, 0}, {0, 1e-300, 1}, r));
    // Above by its centre; radius 0 is a point.
    EXPECT_TRUE(exact::diskAbovePlane(a, b, c, {0, 0, 1e-300}, {0, 0, 1}, 0.0));
    EXPECT_FALSE(exact::diskAbovePlane(a, b, c, {0, 0, 0}, {0, 1, 0}, 0.0));
}

// Coordinates far apart in magnitude (2^-60 next to 2^60) and at the limits of the scene
// loader (2^62): the filter steps aside and the exact path answers.
TEST(ExactSign, ExtremeMagnitudes) {
    const double big = std::ldexp(1.0, 62), tiny = std::ldexp(1.0, -60);
    const dvec3 a(big, 0, 0), b(big, big, 0), c(0, 0, big);
    for (const dvec3& p : {dvec3(tiny, tiny, tiny), dvec3(big, tiny, -tiny), dvec3(0, 0, big),
                           dvec3(-big, big, big), dvec3(1e-310, 0, 0)})
        EXPECT_EQ(exact::orient(a, b, c, p), refOrient(a, b, c, p));
}

}  // namespace
}  // namespace so
