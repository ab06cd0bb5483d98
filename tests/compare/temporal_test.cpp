// temporal_flicker_rate (raster_compare/compare/temporal.h) on synthetic frames with known
// answers: a still camera, a moving one tracked through its motion, surfaces that change, and
// the oracle's own changes (exact and within a sampled light's error).
#include <cmath>
#include <functional>

#include <gtest/gtest.h>

#include "core/camera.h"
#include "core/channels.h"
#include "raster_compare/compare/temporal.h"

namespace so {
namespace {

namespace ch = channels;

constexpr int kW = 40, kH = 30;

// The plane z = 0 seen by `camera`: hit points, one mesh, triangle ids from `prim`, V from
// `vOracle` and `vRaster` (functions of the world point and the pixel).
using VFunc = std::function<float(const glm::dvec3& wsP, int x, int y)>;

struct Frame {
    CameraDesc camera;
    ChannelImage oracle{kW, kH}, raster{kW, kH};
};

Frame makeFrame(const CameraDesc& desc, const VFunc& vOracle, const VFunc& vRaster,
                const std::function<float(int, int)>& prim = nullptr,
                const VFunc& stderrOf = nullptr) {
    Frame f;
    f.camera = desc;
    const Camera camera(desc);
    float* A = f.oracle.addChannel(ch::kHit);
    float* Px = f.oracle.addChannel(ch::kPX);
    float* Py = f.oracle.addChannel(ch::kPY);
    float* Pz = f.oracle.addChannel(ch::kPZ);
    float* mo = f.oracle.addChannel(ch::kMeshId);
    float* po = f.oracle.addChannel(ch::kPrimId);
    float* Vo = f.oracle.addChannel(ch::lightChannel("key", ch::kVisibility));
    float* Co = f.oracle.addChannel(ch::lightChannel("key", ch::kCosine));
    float* SE = stderrOf ? f.oracle.addChannel(ch::lightChannel("key", ch::kStdErr)) : nullptr;
    float* Ar = f.raster.addChannel(ch::kHit);
    float* mr = f.raster.addChannel(ch::kMeshId);
    float* pr = f.raster.addChannel(ch::kPrimId);
    float* Vr = f.raster.addChannel(ch::lightChannel("key", ch::kVisibility));
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            const size_t i = size_t(y) * kW + size_t(x);
            const Ray3d r = camera.generateRay(x, y);
            const double t = -r.origin.z / r.direction.z;
            const glm::dvec3 p = r.origin + t * r.direction;
            A[i] = Ar[i] = 1.0f;
            Px[i] = float(p.x), Py[i] = float(p.y), Pz[i] = float(p.z);
            mo[i] = mr[i] = 0.0f;
            po[i] = pr[i] = prim ? prim(x, y) : 0.0f;
            Co[i] = 1.0f;
            Vo[i] = vOracle(p, x, y);
            Vr[i] = vRaster(p, x, y);
            if (SE) SE[i] = stderrOf(p, x, y);
        }
    return f;
}

CameraDesc lookingDown(double x0) {
    CameraDesc d;
    d.wsEye = {x0, 0.0, 5.0}, d.wsTarget = {x0, 0.0, 0.0}, d.wsUp = {0.0, 1.0, 0.0};
    d.vfovDeg = 40.0, d.width = kW, d.height = kH;
    return d;
}

std::vector<TemporalFrame> frames(const std::vector<Frame>& f) {
    std::vector<TemporalFrame> out;
    for (const Frame& x : f) out.push_back({x.camera, &x.oracle, &x.raster});
    return out;
}

const VFunc kLit = [](const glm::dvec3&, int, int) { return 1.0f; };

TEST(TemporalFlicker, StillCameraCountsExactlyTheToggledPixels) {
    const CameraDesc cam = lookingDown(0.0);
    // Frame 1 toggles 5 pixels of row 3, frame 2 toggles 3 more of row 7 (and keeps row 3).
    auto raster = [](int frame) {
        return [frame](const glm::dvec3&, int x, int y) {
            const bool a = frame >= 1 && y == 3 && x < 5, b = frame >= 2 && y == 7 && x < 3;
            return a || b ? 0.0f : 1.0f;
        };
    };
    std::vector<Frame> f;
    for (int k = 0; k < 3; ++k) f.push_back(makeFrame(cam, kLit, raster(k)));
    const TemporalFlicker r = computeTemporalFlicker(frames(f), "key");
    ASSERT_EQ(r.pairs.size(), 2u);
    EXPECT_EQ(r.pairs[0].tracked, size_t(kW * kH));
    EXPECT_EQ(r.pairs[0].flickering, 5u);
    EXPECT_EQ(r.pairs[1].flickering, 3u);
    EXPECT_EQ(r.tracked, size_t(2 * kW * kH));
    EXPECT_EQ(r.flickering, 8u);
    ASSERT_TRUE(r.rate());
    EXPECT_DOUBLE_EQ(*r.rate(), 8.0 / (2.0 * kW * kH));
    EXPECT_EQ(r.worstPair(), 0u);
    nlohmann::json row;
    r.addToJson(row);
    EXPECT_DOUBLE_EQ(row["temporal_flicker_rate"].get<double>(), 8.0 / (2.0 * kW * kH));
    EXPECT_EQ(row["temporal_tracked_pairs"].get<size_t>(), size_t(2 * kW * kH));
    EXPECT_EQ(row["temporal_frames"].get<size_t>(), 3u);
}

TEST(TemporalFlicker, SmallChangesOfTheRasterAreNotFlicker) {
    const CameraDesc cam = lookingDown(0.0);
    const Frame a = makeFrame(cam, kLit, kLit);
    const Frame b = makeFrame(cam, kLit, [](const glm::dvec3&, int, int) { return 0.55f; });
    const FramePairFlicker p =
        compareFramePair({cam, &a.oracle, &a.raster}, {cam, &b.oracle, &b.raster}, "key");
    EXPECT_EQ(p.flickering, 0u) << "|dV| = 0.45 is not above 0.5";
    EXPECT_EQ(p.tracked, size_t(kW * kH));
}

// A shadow edge fixed in the world, seen by a camera moving sideways: every pixel tracked through
// the motion sees the same V in both frames, so nothing flickers; an edge fixed on the screen
// instead (as a technique that swims would draw it) flips where the world's does not.
TEST(TemporalFlicker, MovingCameraTracksSurfacePoints) {
    const VFunc world = [](const glm::dvec3& p, int, int) { return p.x > 0.3 ? 1.0f : 0.0f; };
    const VFunc screen = [](const glm::dvec3&, int x, int) { return x > kW / 2 ? 1.0f : 0.0f; };
    std::vector<Frame> still, swims;
    for (int k = 0; k < 3; ++k) {
        still.push_back(makeFrame(lookingDown(0.13 * k), world, world));
        swims.push_back(makeFrame(lookingDown(0.13 * k), world, screen));
    }
    const TemporalFlicker r = computeTemporalFlicker(frames(still), "key");
    // The camera moved: some pixels of the next frame are not in the previous one.
    EXPECT_GT(r.tracked, size_t(kW * kH));
    EXPECT_LT(r.tracked, size_t(2 * kW * kH));
    EXPECT_EQ(r.flickering, 0u);
    const TemporalFlicker s = computeTemporalFlicker(frames(swims), "key");
    EXPECT_EQ(s.tracked, r.tracked);
    // Pixel x against pixel x (no tracking) would find none here: the screen edge stays put.
    EXPECT_GT(s.flickering, size_t(kH)) << "at least a column per pair flips";
}

// compare --sequence: a mesh that slides under a still camera is tracked through its known motion
// (MeshMotions). A shadow that stays on the screen while the surface slides under it flips at the
// tracked points; without the motion, pixel x is matched with pixel x and sees nothing.
TEST(TemporalFlicker, MovingMeshIsTrackedThroughItsMotion) {
    const CameraDesc cam = lookingDown(0.0);
    const double step = 0.13;  // world units per frame along x: about a pixel
    const VFunc screen = [](const glm::dvec3&, int x, int) { return x > kW / 2 ? 1.0f : 0.0f; };
    std::vector<Frame> f;
    for (int k = 0; k < 3; ++k) f.push_back(makeFrame(cam, kLit, screen));
    // The plane's point at x in the next frame was at x - step in the previous one.
    const MeshMotions motion = {glm::dmat4(1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0,
                                           0.0, -step, 0.0, 0.0, 1.0)};
    const std::vector<TemporalFrame> t = frames(f);
    const FramePairFlicker without = compareFramePair(t[0], t[1], "key");
    EXPECT_EQ(without.tracked, size_t(kW * kH));
    EXPECT_EQ(without.flickering, 0u);
    const FramePairFlicker with = compareFramePair(t[0], t[1], "key", {}, nullptr, &motion);
    EXPECT_GT(with.tracked, size_t(kW * kH) / 2);
    EXPECT_LT(with.tracked, size_t(kW * kH)) << "the column entering from the left is new";
    EXPECT_GE(with.flickering, size_t(kH)) << "the column under the screen's edge flips";
    // A mesh beyond the motion's list does not move: tracked as without it.
    const MeshMotions none;
    EXPECT_EQ(compareFramePair(t[0], t[1], "key", {}, nullptr, &none).flickering, 0u);
}

TEST(TemporalFlicker, ChangedSurfacesAreNotTracked) {
    const CameraDesc cam = lookingDown(0.0);
    // In frame 1, a 4 x 2 block shows another triangle, and the raster's V changes there.
    auto block = [](int x, int y) { return x >= 10 && x < 14 && y >= 5 && y < 7; };
    const Frame a = makeFrame(cam, kLit, kLit);
    const Frame b = makeFrame(
        cam, kLit, [&](const glm::dvec3&, int x, int y) { return block(x, y) ? 0.0f : 1.0f; },
        [&](int x, int y) { return block(x, y) ? 1.0f : 0.0f; });
    std::vector<uint8_t> mask;
    const FramePairFlicker p = compareFramePair({cam, &a.oracle, &a.raster},
                                                {cam, &b.oracle, &b.raster}, "key", {}, &mask);
    EXPECT_EQ(p.tracked, size_t(kW * kH - 8));
    EXPECT_EQ(p.flickering, 0u);
    EXPECT_EQ(mask[size_t(5) * kW + 10], 0);
    EXPECT_EQ(mask[0], 1);
}

TEST(TemporalFlicker, OracleChangesAreExcluded) {
    const CameraDesc cam = lookingDown(0.0);
    // The light moved (as it were): both the oracle and the raster change in row 2; the raster
    // alone changes in row 4.
    const VFunc before = kLit;
    const VFunc oracleAfter = [](const glm::dvec3&, int, int y) { return y == 2 ? 0.0f : 1.0f; };
    const VFunc rasterAfter = [](const glm::dvec3&, int, int y) {
        return y == 2 || y == 4 ? 0.0f : 1.0f;
    };
    const Frame a = makeFrame(cam, before, before);
    const Frame b = makeFrame(cam, oracleAfter, rasterAfter);
    std::vector<uint8_t> mask;
    const FramePairFlicker p = compareFramePair({cam, &a.oracle, &a.raster},
                                                {cam, &b.oracle, &b.raster}, "key", {}, &mask);
    EXPECT_EQ(p.flickering, size_t(kW));
    EXPECT_EQ(mask[size_t(4) * kW], 2);
    EXPECT_EQ(mask[size_t(2) * kW], 1);
}

// Sampled area lights: the oracle's change counts only beyond 3 sqrt(se^2 + se'^2) + 1e-6.
TEST(TemporalFlicker, SampledOracleChangeWithinItsErrorIsNoChange) {
    const CameraDesc cam = lookingDown(0.0);
    const VFunc half = [](const glm::dvec3&, int, int) { return 0.5f; };
    const VFunc halfAndABit = [](const glm::dvec3&, int, int) { return 0.6f; };
    const VFunc rasterAfter = [](const glm::dvec3&, int, int) { return 0.0f; };
    const VFunc rasterBefore = [](const glm::dvec3&, int, int) { return 1.0f; };
    for (const float se : {0.05f, 0.01f}) {
        const VFunc stderrOf = [se](const glm::dvec3&, int, int) { return se; };
        const Frame a = makeFrame(cam, half, rasterBefore, nullptr, stderrOf);
        const Frame b = makeFrame(cam, halfAndABit, rasterAfter, nullptr, stderrOf);
        const FramePairFlicker p =
            compareFramePair({cam, &a.oracle, &a.raster}, {cam, &b.oracle, &b.raster}, "key");
        // dVo = 0.1: within 3 * 0.0707 = 0.21, beyond 3 * 0.0141 = 0.042.
        EXPECT_EQ(p.flickering, se == 0.05f ? size_t(kW * kH) : 0u) << "stderr " << se;
    }
}

TEST(TemporalFlicker, NothingTrackedHasNoRate) {
    const TemporalFlicker none;
    EXPECT_FALSE(none.rate());
    nlohmann::json row;
    none.addToJson(row);
    EXPECT_TRUE(row["temporal_flicker_rate"].is_null());
}

}  // namespace
}  // namespace so
