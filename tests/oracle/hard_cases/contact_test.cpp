// Case 2 (docs/hard-cases.md): a box resting on the floor and hovering 1e-3, 1e-5 and 1e-7 of the
// scene's size above it, lit by a point light at an angle. Image level: every floor pixel against
// the exact segment-box test in double. Under the box (no camera sees there at small gaps): the
// oracle's hard-shadow pass at floor points across the light-side edge, where a hovering box's
// shadow detaches by gap (Lx - 1) / (Ly - gap), the projection of its bottom face. Where the oracle
// differs from the exact answer, the segment must pass within the blind distance of the box
// (oracle.json offset_policy.max_blind_distance).
#include <algorithm>
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "case_scenes.h"
#include "core/channels.h"
#include "hard_scenes.h"

namespace so::test::hard {
namespace {

namespace ch = channels;

struct ContactCount {
    size_t floor = 0, mismatches = 0, beyondBlind = 0;
    double worstMismatchMargin = 0.0;          // the largest margin of a point the oracle got wrong
    size_t contactShadow = 0, contactLit = 0;  // far side, within 0.1 of the foot: exact shadow
};

// The float channels round the hit point by up to half an ulp of its largest coordinate.
double roundingSlack(const glm::dvec3& p) {
    const float m = float(std::max({std::fabs(p.x), std::fabs(p.y), std::fabs(p.z)}));
    return 2.0 * double(std::nextafter(m, INFINITY) - m);
}

// One floor point against the exact answer; returns whether the oracle agrees.
bool countPoint(const ContactScene& c, const glm::dvec3& p, float v, double blind,
                ContactCount& n) {
    ++n.floor;
    const bool occluded = segmentHitsBox(p, c.wsLight, c.boxLo, c.boxHi, 0.0);
    const bool agrees = v == (occluded ? 0.0f : 1.0f);
    if (!agrees) {
        const double margin = boxMargin(p, c.wsLight, c.boxLo, c.boxHi, 1.0);
        ++n.mismatches;
        n.worstMismatchMargin = std::max(n.worstMismatchMargin, margin);
        n.beyondBlind += margin > blind + roundingSlack(p);
    }
    // The far side of the foot's edge x = -1 (the light is at x = 3.5): the shadow's contact line.
    const double fromFoot = -1.0 - p.x;
    if (occluded && std::fabs(p.z) < 0.9 && fromFoot > 0.0 && fromFoot < 0.1)
        ++(v == 0.0f ? n.contactShadow : n.contactLit);
    return agrees;
}

void checkImage(double gapRelative, bool zoomed) {
    const ContactScene c = makeContactScene(gapRelative, zoomed, zoomed ? 128 : 160);
    OracleResult r = runHard(c.scene);
    const double blind = r.stats.offsetPolicy.maxBlindDistance;
    const float* A = r.image.channel(ch::kHit);
    const float* mesh = r.image.channel(ch::kMeshId);
    const float* V = r.image.channel(ch::lightChannel("key", ch::kVisibility));
    ContactCount n;
    for (size_t i = 0; i < r.image.pixelCount(); ++i) {
        if (A[i] == 0.0f || mesh[i] != 0.0f) continue;
        glm::dvec3 p = hitPoint(r.image, i);
        p.y = 0.0;  // on the floor exactly (the channel's rounding is off the plane only)
        countPoint(c, p, V[i], blind, n);
    }
    std::printf(
        "[ hard ] contact gap %g (%.3g units), %s view: %zu floor px, %zu differ from "
        "exact (%zu beyond the blind distance %.3g, worst margin %.3g); far-side "
        "contact line: %zu px shadowed, %zu lit\n",
        gapRelative, c.gap, zoomed ? "zoomed" : "wide", n.floor, n.mismatches, n.beyondBlind, blind,
        n.worstMismatchMargin, n.contactShadow, n.contactLit);
    EXPECT_EQ(nonFiniteValues(r.image), 0u);
    EXPECT_GT(n.floor, 1000u);
    EXPECT_EQ(n.beyondBlind, 0u) << "a miss farther than the blind distance";
    // The far side's shadow reaches the foot at every gap (the bottom face shadows it), and
    // resting, the ambiguous pixels at the contact line included.
    EXPECT_EQ(n.contactLit, 0u);
    EXPECT_GT(n.contactShadow, zoomed ? 500u : 20u);
    if (gapRelative == 0.0) {
        EXPECT_EQ(n.mismatches, 0u);
    }
}

TEST(HardContact, ImageRestingAndHoveringBoxShadowReachesTheFoot) {
    for (double g : kContactGaps) {
        checkImage(g, false);
        checkImage(g, true);
    }
}

// Floor points under the box across its light-side edge x = 1 at z = z0: lit where the segment
// passes under the edge, exactly for 1 - x < gap (Lx - 1) / (Ly - gap) at z0 = 0.
void checkUnderTheBox(double gapRelative) {
    const ContactScene c = makeContactScene(gapRelative, false, 16);
    const double band = c.gap * (c.wsLight.x - 1.0) / (c.wsLight.y - c.gap);
    const double range = std::max(4.0 * band, 1e-4);
    const int count = 4096;
    std::vector<glm::dvec3> points;
    for (int k = 0; k < count; ++k) points.push_back({1.0 - range * (k + 0.5) / count, 0.0, 0.0});
    const PointVisibility pv = oracleVisibilityAt(c.scene, 0, points, {0, 1, 0});
    ASSERT_EQ(pv.missed, 0u);
    ContactCount n;
    double measured = 0.0;  // the lit strip from the edge, as the oracle sees it
    bool strip = true;
    for (int k = 0; k < count; ++k) {
        countPoint(c, pv.wsPoints[size_t(k)], pv.V[size_t(k)], pv.blindDistance, n);
        strip = strip && pv.V[size_t(k)] == 1.0f;
        if (strip) measured = 1.0 - pv.wsPoints[size_t(k)].x;
    }
    const double step = range / count;
    std::printf(
        "[ hard ] contact gap %g (%.3g units), under the box: lit strip %.4g wide, closed "
        "form %.4g (blind distance %.3g); %zu of %zu points differ from exact (%zu beyond "
        "the blind distance, worst margin %.3g)\n",
        gapRelative, c.gap, measured, band, pv.blindDistance, n.mismatches, n.floor, n.beyondBlind,
        n.worstMismatchMargin);
    EXPECT_EQ(n.beyondBlind, 0u) << "a miss farther than the blind distance";
    // The strip is the closed form's to within the blind distance and the points' spacing.
    EXPECT_LE(measured, band + step);
    EXPECT_GE(measured, band - pv.blindDistance - step);
    if (band > 4.0 * pv.blindDistance) {
        EXPECT_GT(measured, 0.0) << "the shadow must detach";
    }
}

TEST(HardContact, UnderTheBoxShadowDetachesByTheGeometricAmount) {
    for (double g : kContactGaps) checkUnderTheBox(g);
}

}  // namespace
}  // namespace so::test::hard
