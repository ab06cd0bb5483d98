// Ghosting and acne without a depth comparison (docs/metrics.md#sequence, issue 64) on synthetic
// images with known answers: a false shadow where the truth just changed is ghosting, not acne,
// away from the oracle's boundary only; a family that compares no depth has no acne; and a
// SequenceJudge over a shadow sliding under a still camera, with a technique two frames behind,
// counts exactly the trail's pixels that a direct count finds.
#include <algorithm>
#include <cstdlib>
#include <vector>

#include <gtest/gtest.h>

#include "core/camera.h"
#include "core/channels.h"
#include "raster_compare/compare/metrics.h"
#include "raster_compare/compare/sequence_judge.h"

namespace so {
namespace {

namespace ch = channels;

constexpr int kW = 64, kH = 8;

// A hard light's V along x, the same on every row: 0 inside [begin, end), 1 elsewhere.
struct Shadow {
    int begin, end;
    float at(int x) const { return x >= begin && x < end ? 0.0f : 1.0f; }
};

// The plane z = 0 seen from above, every pixel one triangle facing the light; V by column.
struct Frame {
    CameraDesc camera;
    ChannelImage oracle{kW, kH}, raster{kW, kH};
};

CameraDesc lookingDown() {
    CameraDesc d;
    d.wsEye = {0.0, 0.0, 5.0}, d.wsTarget = {0.0, 0.0, 0.0}, d.wsUp = {0.0, 1.0, 0.0};
    d.vfovDeg = 40.0, d.width = kW, d.height = kH;
    return d;
}

void fillImage(ChannelImage& img, const Camera& camera, const std::vector<float>& vByColumn,
               bool positions) {
    float* A = img.addChannel(ch::kHit, 1.0f);
    img.addChannel(ch::kMeshId, 0.0f);
    img.addChannel(ch::kPrimId, 0.0f);
    img.addChannel(ch::lightChannel("key", ch::kCosine), 1.0f);
    float* V = img.addChannel(ch::lightChannel("key", ch::kVisibility));
    float* P[3] = {nullptr, nullptr, nullptr};
    if (positions)
        P[0] = img.addChannel(ch::kPX), P[1] = img.addChannel(ch::kPY),
        P[2] = img.addChannel(ch::kPZ);
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            const size_t i = size_t(y) * kW + size_t(x);
            A[i] = 1.0f;
            V[i] = vByColumn[size_t(x)];
            if (!positions) continue;
            const Ray3d r = camera.generateRay(x, y);
            const glm::dvec3 p = r.origin + (-r.origin.z / r.direction.z) * r.direction;
            P[0][i] = float(p.x), P[1][i] = float(p.y), P[2][i] = float(p.z);
        }
}

Frame makeFrame(const std::vector<float>& oracleV, const std::vector<float>& rasterV) {
    Frame f;
    f.camera = lookingDown();
    const Camera camera(f.camera);
    fillImage(f.oracle, camera, oracleV, true);
    fillImage(f.raster, camera, rasterV, false);
    return f;
}

std::vector<float> columns(const Shadow& s) {
    std::vector<float> v(kW);
    for (int x = 0; x < kW; ++x) v[size_t(x)] = s.at(x);
    return v;
}

// Every pixel of these columns.
std::vector<uint8_t> maskOfColumns(int begin, int end) {
    std::vector<uint8_t> m(size_t(kW) * kH, 0);
    for (int y = 0; y < kH; ++y)
        for (int x = begin; x < end; ++x) m[size_t(y) * kW + size_t(x)] = 1;
    return m;
}

// The truth's shadow at [10, 18); the technique keeps an old one at [30, 36) (a trail, 12 pixels
// from the truth's boundary) and shadows [50, 52) by itself.
struct TrailCase {
    Frame frame;
    TrailCase() {
        std::vector<float> r = columns({10, 18});
        for (int x = 30; x < 36; ++x) r[size_t(x)] = 0.0f;
        for (int x = 50; x < 52; ++x) r[size_t(x)] = 0.0f;
        frame = makeFrame(columns({10, 18}), r);
    }
};

TEST(Ghosting, AFalseShadowWhereTheTruthJustChangedIsGhostingNotAcne) {
    const TrailCase c;
    MetricOptions options;
    const LightMetrics before = computeLightMetrics(c.frame.oracle, c.frame.raster, "key", options);
    // Fully lit and more than 2 pixels from the boundary (the lit boundary pixels are x = 9 and
    // 18): x < 7, 21 <= x: 7 + 43 columns; acne: the trail's 6 and the speckle's 2 columns.
    EXPECT_DOUBLE_EQ(before.acneRate, 8.0 / 50.0);
    EXPECT_EQ(before.ghostingEligible, 0u);

    // The truth changed at [26, 40) and, within the band, at [17, 20).
    std::vector<uint8_t> changed = maskOfColumns(26, 40);
    for (size_t i = 0; i < changed.size(); ++i) changed[i] |= maskOfColumns(17, 20)[i];
    options.truthChanged = &changed;
    ErrorMaps maps;
    const LightMetrics m =
        computeLightMetrics(c.frame.oracle, c.frame.raster, "key", options, &maps);
    EXPECT_EQ(m.ghostingEligible, size_t(14 * kH)) << "[17, 20) is within r of the boundary";
    EXPECT_EQ(m.ghostingPixels, size_t(6 * kH));
    EXPECT_DOUBLE_EQ(m.acneRate, 2.0 / 50.0) << "the speckle stays acne";
    EXPECT_EQ(m.otherFalseShadowRate, 0.0);
    EXPECT_EQ(m.mae, before.mae);
    const size_t trail = size_t(2) * kW + 32, speckle = size_t(2) * kW + 50;
    EXPECT_EQ(maps.shown[trail], 1 + size_t(Artifact::Ghosting));
    EXPECT_EQ(maps.of(Artifact::Ghosting)[trail], 1.0f);
    EXPECT_EQ(maps.of(Artifact::Acne)[trail], 0.0f);
    EXPECT_EQ(maps.shown[speckle], 1 + size_t(Artifact::Acne));
    EXPECT_EQ(maps.of(Artifact::Ghosting)[speckle], 0.0f);
}

// On an area light a pixel of the oracle's penumbra (0 < O < 1) is judged by the penumbra's
// metrics, whatever came before: no ghosting there, even where its truth changed.
TEST(Ghosting, InTheOraclesPenumbraAWrongPixelIsNotGhosting) {
    std::vector<float> o = columns({10, 18}), r = o;
    for (int x = 18; x < 26; ++x) o[size_t(x)] = 0.25f;  // a penumbra, r lit there
    Frame f = makeFrame(o, r);
    f.oracle.addChannel(ch::lightChannel("key", ch::kStdErr), 0.0f);
    for (int x = 30; x < 34; ++x)  // and a trail on lit pixels
        for (int y = 0; y < kH; ++y)
            f.raster.channel(ch::lightChannel("key", ch::kVisibility))[size_t(y) * kW + x] = 0.5f;
    const std::vector<uint8_t> changed = maskOfColumns(18, 40);
    MetricOptions options;
    options.truthChanged = &changed;
    ErrorMaps maps;
    const LightMetrics m = computeLightMetrics(f.oracle, f.raster, "key", options, &maps);
    // The lit boundary pixel is x = 26: of [18, 40), [29, 40) are more than 2 away and lit.
    EXPECT_EQ(m.ghostingEligible, size_t(11 * kH));
    EXPECT_EQ(m.ghostingPixels, size_t(4 * kH));
    EXPECT_EQ(maps.shown[size_t(2) * kW + 20], 1 + size_t(Artifact::Penumbra));
    EXPECT_EQ(maps.of(Artifact::Ghosting)[size_t(2) * kW + 20], 0.0f);
}

TEST(Ghosting, AFamilyWithoutDepthComparisonHasNoAcne) {
    EXPECT_FALSE(familyComparesDepth("ray tracing"));
    EXPECT_FALSE(familyComparesDepth("shadow texture"));
    EXPECT_FALSE(familyComparesDepth("planar projection"));
    for (const char* f : {"shadow map", "virtual shadow map", "accumulation", "screen-space blur",
                          "lightmap", "shadow volume", "external"})
        EXPECT_TRUE(familyComparesDepth(f)) << f;

    const TrailCase c;
    MetricOptions options;
    options.comparesDepth = false;
    ErrorMaps maps;
    const LightMetrics m =
        computeLightMetrics(c.frame.oracle, c.frame.raster, "key", options, &maps);
    EXPECT_EQ(m.acneRate, 0.0);
    // The trail's and the speckle's 8 columns, of 64: other false shadow, as no class explains
    // them.
    EXPECT_DOUBLE_EQ(m.otherFalseShadowRate, 8.0 / 64.0);
    EXPECT_EQ(maps.shown[size_t(2) * kW + 50], 1 + size_t(Artifact::OtherFalseShadow));
}

TEST(Ghosting, TheMaskMustMatchTheImages) {
    const TrailCase c;
    const std::vector<uint8_t> wrong(10, 1);
    MetricOptions options;
    options.truthChanged = &wrong;
    EXPECT_THROW(computeLightMetrics(c.frame.oracle, c.frame.raster, "key", options),
                 std::invalid_argument);
}

// The shadow [4 + 4k, 12 + 4k) of frame k; the technique shows frame k - lag's.
Shadow slidingShadow(int k) {
    return {4 + 4 * k, 12 + 4 * k};
}

// What the judge must find, counted directly: per frame, the columns whose truth differs by more
// than 0.5 from one of the 4 frames before, those more than 2 columns from a lit boundary column
// (a lit column beside a shadowed one), and those of them where the technique is wrong.
struct Expected {
    size_t lag = 0, eligible = 0, ghost = 0;
};
Expected countDirectly(int frames, int lag) {
    Expected e;
    for (int k = 0; k < frames; ++k) {
        const Shadow now = slidingShadow(k), shown = slidingShadow(std::max(0, k - lag));
        for (int x = 0; x < kW; ++x) {
            bool changed = false;
            for (int j = std::max(0, k - 4); j < k; ++j)
                changed = changed || slidingShadow(j).at(x) != now.at(x);
            if (!changed) continue;
            e.lag += kH;
            int toBoundary = kW;
            for (int b = 0; b < kW; ++b) {
                const bool lit = now.at(b) == 1.0f;
                const bool edge =
                    (b > 0 && now.at(b - 1) == 0.0f) || (b + 1 < kW && now.at(b + 1) == 0.0f);
                if (lit && edge) toBoundary = std::min(toBoundary, std::abs(x - b));
            }
            if (toBoundary <= 2) continue;
            e.eligible += kH;
            if (shown.at(x) != now.at(x)) e.ghost += kH;
        }
    }
    return e;
}

SequenceMetrics judgeSlidingShadow(int frames, int lag, MetricOptions options = {}) {
    SequenceJudge judge("key", options);
    std::vector<Frame> kept(2);
    for (int k = 0; k < frames; ++k) {
        Frame& f = kept[size_t(k) % 2];
        f = makeFrame(columns(slidingShadow(k)), columns(slidingShadow(std::max(0, k - lag))));
        judge.add({{f.camera, &f.oracle, &f.raster}, nullptr});
    }
    return judge.metrics();
}

TEST(Ghosting, TheJudgeCountsATrailTwoFramesBehind) {
    const int frames = 10;
    const Expected e = countDirectly(frames, 2);
    const SequenceMetrics s = judgeSlidingShadow(frames, 2);
    EXPECT_EQ(s.lagPixels, e.lag);
    EXPECT_EQ(s.ghostingEligible, e.eligible);
    EXPECT_EQ(s.ghostingPixels, e.ghost);
    ASSERT_GT(e.ghost, 0u);
    ASSERT_TRUE(s.ghostingRate());
    EXPECT_DOUBLE_EQ(*s.ghostingRate(), double(e.ghost) / double(e.eligible));
    const nlohmann::json j = s.toJson();
    EXPECT_EQ(j["ghosting_pixels"], e.ghost);
    EXPECT_DOUBLE_EQ(j["ghosting_rate"].get<double>(), *s.ghostingRate());

    // The last frame judged with its mask: the trail (4 pixels behind the truth's shadow, 8 wide)
    // is acne without it, ghosting with it.
    const Frame last =
        makeFrame(columns(slidingShadow(frames - 1)), columns(slidingShadow(frames - 3)));
    MetricOptions options;
    EXPECT_GT(computeLightMetrics(last.oracle, last.raster, "key", options).acneRate, 0.0);
    options.truthChanged = &s.lastTruthChanged;
    const LightMetrics m = computeLightMetrics(last.oracle, last.raster, "key", options);
    EXPECT_EQ(m.acneRate, 0.0);
    EXPECT_GT(m.ghostingPixels, 0u);
}

TEST(Ghosting, ATechniqueThatKeepsUpLeavesNoGhost) {
    const SequenceMetrics s = judgeSlidingShadow(10, 0);
    EXPECT_GT(s.ghostingEligible, 0u);
    EXPECT_EQ(s.ghostingPixels, 0u);
    ASSERT_TRUE(s.ghostingRate());
    EXPECT_EQ(*s.ghostingRate(), 0.0);
}

TEST(Ghosting, AStillTruthHasNoRate) {
    SequenceJudge judge("key", {});
    const Frame f = makeFrame(columns({10, 18}), columns({30, 36}));
    for (int k = 0; k < 3; ++k) judge.add({{f.camera, &f.oracle, &f.raster}, nullptr});
    EXPECT_FALSE(judge.metrics().ghostingRate());
    EXPECT_EQ(judge.metrics().ghostingPixels, 0u);
    EXPECT_TRUE(judge.metrics().toJson()["ghosting_rate"].is_null());
}

}  // namespace
}  // namespace so
