// Case 4 (docs/hard-cases.md): every hard case translated by 2^17 and 2^20 and scaled by 2^-10
// and 2^10 gives the very same bits (hit, ids, and every light's V and cos), because the oracle
// recentres and rescales in double before anything becomes float (core/local_frame.h). The
// existing test (tests/oracle/closed_form_test.cpp, Invariance.*) covers 2^16 on the square
// occluder.
#include <cmath>
#include <cstdio>
#include <cstring>

#include <gtest/gtest.h>

#include "case_scenes.h"
#include "hard_scenes.h"

namespace so::test::hard {
namespace {

struct Transform {
    double scale;
    glm::dvec3 t;
    const char* name;
};

const Transform kTransforms[] = {
    {1.0, {131072.0, 131072.0, -131072.0}, "translate 2^17"},
    {1.0, {1048576.0, -1048576.0, 1048576.0}, "translate 2^20"},
    {0x1.0p-10, {0, 0, 0}, "scale 2^-10"},
    {0x1.0p10, {0, 0, 0}, "scale 2^10"},
    {0x1.0p10, {1048576.0, 0.0, -1048576.0}, "scale 2^10, translate 2^20"},
};

// Runs `scene` as is and under every transform; returns the channels that differed.
int checkScene(const Scene& scene, const char* what) {
    const ChannelImage ref = runHard(scene).image;
    const std::vector<std::string> names = invariantChannels(scene);
    int differing = 0;
    for (const Transform& tr : kTransforms) {
        const ChannelImage img = runHard(transformScene(scene, tr.scale, tr.t)).image;
        std::string first;
        const int n = differingChannels(ref, img, names, &first);
        EXPECT_EQ(n, 0) << what << ", " << tr.name << ": " << first << " differs first";
        differing += n;
    }
    std::printf("[ hard ] far from the origin: %s, %zu channels x %zu transforms: %d differ\n",
                what, names.size(), std::size(kTransforms), differing);
    return differing;
}

TEST(HardFarFromOrigin, GrazingIsBitIdentical) {
    checkScene(makeGrazingScene(false, 48).scene, "grazing, flat plane");
    checkScene(makeGrazingScene(true, 48).scene, "grazing, tilted plane");
}

TEST(HardFarFromOrigin, ContactIsBitIdentical) {
    for (double g : kContactGaps) {
        char what[64];
        std::snprintf(what, sizeof what, "contact gap %g", g);
        checkScene(makeContactScene(g, false, 96).scene, (std::string(what) + ", wide").c_str());
        checkScene(makeContactScene(g, true, 64).scene, (std::string(what) + ", zoomed").c_str());
    }
}

// The oracle's pass at floor points under the box (contact_test.cpp), the points moved with the
// scene (on a 2^-32 grid, so the move is exact).
TEST(HardFarFromOrigin, UnderTheBoxPointsAreBitIdentical) {
    int differing = 0;
    for (double g : kContactGaps) {
        const ContactScene c = makeContactScene(g, false, 16);
        std::vector<glm::dvec3> points;
        const double range = std::max(4.0 * c.gap, 1e-4);
        for (int k = 0; k < 1024; ++k)
            points.push_back(snap(glm::dvec3(1.0 - range * (k + 0.5) / 1024, 0.0, 0.0), 32));
        const PointVisibility ref = oracleVisibilityAt(c.scene, 0, points, {0, 1, 0});
        for (const Transform& tr : kTransforms) {
            std::vector<glm::dvec3> moved;
            for (const glm::dvec3& p : points) moved.push_back(p * tr.scale + tr.t);
            const PointVisibility pv =
                oracleVisibilityAt(transformScene(c.scene, tr.scale, tr.t), 0, moved, {0, 1, 0});
            const bool same =
                std::memcmp(ref.V.data(), pv.V.data(), ref.V.size() * sizeof(float)) == 0;
            EXPECT_TRUE(same) << "gap " << g << ", " << tr.name;
            differing += !same;
        }
    }
    std::printf(
        "[ hard ] far from the origin: under-the-box points, 4 gaps x %zu transforms: %d "
        "differ\n",
        std::size(kTransforms), differing);
}

TEST(HardFarFromOrigin, ClosedMeshesAreBitIdentical) {
    for (uint64_t seed : {1u, 2u}) {
        checkScene(makeClosedMeshScene(false, seed, 96).scene, "closed cube");
        checkScene(makeClosedMeshScene(true, seed, 96).scene, "closed icosphere");
    }
}

// The invariance above is only worth something if a change below the float spacing at 2^20 shows.
TEST(HardFarFromOrigin, ASubFloatMoveWouldBeVisible) {
    const ContactScene c = makeContactScene(1e-3, false, 96);
    Scene moved = c.scene;
    for (glm::dvec3& p : moved.meshes[1].wsPositions)
        p.x += 1.0 / 32.0;  // float spacing at 2^20: 1/8
    finalizeScene(moved);
    std::string first;
    EXPECT_GT(differingChannels(runHard(c.scene).image, runHard(moved).image,
                                invariantChannels(c.scene), &first),
              0);
}

}  // namespace
}  // namespace so::test::hard
