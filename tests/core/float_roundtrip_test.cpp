// The project's code-generation guard (cmake/float_roundtrip_check.cmake): GCC 12.2's SLP
// vectorizer drops the double -> float rounding of the first two of three coordinates rounded in
// one expression. This file is compiled with the project's flags, so it fails on such a compiler
// if the guard that adds -fno-tree-slp-vectorize goes missing.
#include <gtest/gtest.h>
#include <glm/glm.hpp>

namespace {

struct D3 {
    double x, y, z;
};

__attribute__((noinline)) D3 roundEach(D3 p) {
    return D3{double(float(p.x)), double(float(p.y)), double(float(p.z))};
}

__attribute__((noinline)) glm::dvec3 roundThroughGlm(const glm::dvec3& p) {
    return glm::dvec3(glm::vec3(p));
}

}  // namespace

TEST(FloatRoundTrip, ThreeCoordinatesInOneExpressionAreEachRounded) {
    volatile double e = 1e-12;  // not a constant the compiler could fold
    const D3 r = roundEach(D3{1.0 + e, 2.0 + e, 4.0 + e});
    EXPECT_EQ(r.x, 1.0);
    EXPECT_EQ(r.y, 2.0);
    EXPECT_EQ(r.z, 4.0);
    const glm::dvec3 g = roundThroughGlm(glm::dvec3(1.0 + e, 2.0 + e, 4.0 + e));
    EXPECT_EQ(g.x, 1.0);
    EXPECT_EQ(g.y, 2.0);
    EXPECT_EQ(g.z, 4.0);
}
