// Generated scenes for the oracle's hard-case suite (docs/hard-cases.md, ctest label "hard"):
// grazing light, contact, closed meshes, far from the origin, degenerate input. Every position is
// dyadic with few significant bits, so translating by 2^20 or scaling by 2^k is exact in double and
// the oracle must give the very same bits.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

#include "core/image.h"
#include "core/scene.h"
#include "oracle/oracle.h"
#include "test_scenes.h"  // transformScene

namespace so::test::hard {

// Rounds v to a multiple of 2^-bits.
double snap(double v, int bits);
glm::dvec3 snap(const glm::dvec3& v, int bits);
// Snaps every mesh vertex, light position, area-light edge and the camera to 2^-bits.
void snapScene(Scene& scene, int bits);

// A closed icosphere (subdivided icosahedron projected on the sphere), outward triangles.
MeshPrimitive makeIcosphere(const glm::dvec3& c, double r, int subdivisions,
                            const std::string& name);
// A rotation drawn from a seeded generator (portable: no std distributions).
glm::dmat3 randomRotation(uint64_t seed);
// Rotates the mesh about `center`.
void rotateMesh(MeshPrimitive& mesh, const glm::dmat3& r, const glm::dvec3& center);

// Runs the oracle quietly (all threads), image and stats.
OracleResult runHard(const Scene& scene, PenumbraMethod penumbra = PenumbraMethod::Auto);

// Channels that must not move when the scene moves: hit, ids, and per light V and cos.
std::vector<std::string> invariantChannels(const Scene& scene);
// Number of channels among `names` whose bits differ.
int differingChannels(const ChannelImage& a, const ChannelImage& b,
                      const std::vector<std::string>& names, std::string* first);
// NaNs in any channel, and infinities outside the depth and occ_dist channels (where they mean
// "nothing there").
size_t nonFiniteValues(const ChannelImage& img);

// The oracle's hard-shadow pass (traceHardShadows, the same packets, offsets and filter) at chosen
// receiver points instead of pixels: each point is found on the receiver by a probe ray along
// wsNormal from 2^-10 local units below it, its hit point rebuilt on the double triangle as the
// primary pass does, the normal set to wsNormal (the lit side).
struct PointVisibility {
    std::vector<float> V;              // per point (0 where the probe ray found no surface)
    std::vector<glm::dvec3> wsPoints;  // the rebuilt hit points, world space
    size_t missed = 0;                 // probe rays that found no surface
    double blindDistance = 0.0;        // world units: the largest origin offset used
};
PointVisibility oracleVisibilityAt(const Scene& scene, size_t light,
                                   const std::vector<glm::dvec3>& wsPoints,
                                   const glm::dvec3& wsNormal);

// The world-space hit point of pixel i (float channels).
glm::dvec3 hitPoint(const ChannelImage& img, size_t i);

// The closed segment p -> q against the axis-aligned box [lo - e, hi + e] (slab test in double;
// e may be negative: the box shrunk).
bool segmentHitsBox(const glm::dvec3& p, const glm::dvec3& q, const glm::dvec3& lo,
                    const glm::dvec3& hi, double e);
// The largest e (bisection, to 2^-50 relative) at which the box grown and shrunk by e give the same
// answer: how far the segment is from changing its answer (L-infinity).
double boxMargin(const glm::dvec3& p, const glm::dvec3& q, const glm::dvec3& lo,
                 const glm::dvec3& hi, double eMax);

}  // namespace so::test::hard
