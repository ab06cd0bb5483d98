// smrt, shadow-map ray tracing (Unreal 5's SMRT, issue 54), on the closed-form penumbra scene: a
// rect light over a parallel square occluder. Its rays toward points on the light give a penumbra
// that the hard slope-bias has not, close to pcss's, which Fernando derived for exactly these
// parallel planes. Label "gl".
#include <cstdio>
#include <string>

#include <gtest/gtest.h>

#include "gl_test_context.h"
#include "raster_compare/compare/metrics.h"
#include "test_scenes.h"

namespace so::test {
namespace {

TEST(Smrt, PenumbraOfARectLightOverAParallelOccluder) {
    REQUIRE_GL();
    const Scene s = makePenumbraScene(128, 96).scene;
    const ChannelImage o = runQuiet(s);
    const auto metrics = [&](const std::string& t) {
        const LightMetrics m =
            computeLightMetrics(o, renderOneFrame(s, t, {}, false).image, "panel", {});
        EXPECT_TRUE(m.penumbraMae && m.penumbraWidth) << t;
        std::printf("[ smrt ] %-10s penumbra_mae %.4f penumbra width error %.2f px (oracle %.2f)\n",
                    t.c_str(), m.penumbraMae.value_or(-1),
                    m.penumbraWidth ? m.penumbraWidth->mean : -1.0,
                    m.penumbraWidth ? m.penumbraWidth->oracleMeanWidth : -1.0);
        return m;
    };
    const LightMetrics smrt = metrics("smrt"), hard = metrics("slope-bias"), pcss = metrics("pcss");
    ASSERT_TRUE(smrt.penumbraMae && hard.penumbraMae && pcss.penumbraMae);
    ASSERT_TRUE(smrt.penumbraWidth && hard.penumbraWidth);
    EXPECT_LT(*smrt.penumbraMae, *hard.penumbraMae);
    EXPECT_LT(smrt.penumbraWidth->mean, hard.penumbraWidth->mean);
    EXPECT_LE(*smrt.penumbraMae, 1.5 * *pcss.penumbraMae);
}

}  // namespace
}  // namespace so::test
