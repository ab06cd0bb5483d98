// Error against cost (raster_compare/compare/tradeoff.h): the Pareto front, the quality curves,
// the cheapest setting within a budget and the oracle's time at an error, on hand-made points
// whose answers are known.
#include <cmath>

#include <gtest/gtest.h>

#include "raster_compare/compare/tradeoff.h"

namespace so::test {
namespace {

std::vector<TradeoffPoint> points() {
    return {{"a:n=4", "a", 4.0, 10.0, 0.20},      {"a:n=16", "a", 16.0, 40.0, 0.05},
            {"a:n=64", "a", 64.0, 160.0, 0.01},   {"b", "b", std::nullopt, 5.0, 0.30},
            {"c", "c", std::nullopt, 50.0, 0.10}, {"d:n=1", "d", 1.0, 10.0, 0.25}};
}

TEST(Tradeoff, ParetoFrontKeepsOnlyUnbeatenSettings) {
    const std::vector<size_t> front = paretoFront(points());
    // b is cheapest; a:n=4 beats d (same time, lower error); c is beaten by a:n=16.
    EXPECT_EQ(front, (std::vector<size_t>{3, 0, 1, 2}));
}

TEST(Tradeoff, CurvesJoinSettingsThatDifferOnlyInQuality) {
    std::vector<TradeoffPoint> p = points();
    std::swap(p[0], p[2]);  // given out of order: the curve is sorted by quality
    const std::vector<TradeoffCurve> curves = qualityCurves(p);
    ASSERT_EQ(curves.size(), 1u) << "d has one point: no curve";
    EXPECT_EQ(curves[0].key, "a");
    ASSERT_EQ(curves[0].points.size(), 3u);
    EXPECT_EQ(*p[curves[0].points[0]].quality, 4.0);
    EXPECT_EQ(*p[curves[0].points[2]].quality, 64.0);
}

TEST(Tradeoff, CheapestWithinABudget) {
    const std::vector<TradeoffPoint> p = points();
    EXPECT_EQ(cheapestWithin(p, 0.3), 3u);
    EXPECT_EQ(cheapestWithin(p, 0.2), 0u);
    EXPECT_EQ(cheapestWithin(p, 0.1), 1u) << "a:n=16 (40 ms) before c (50 ms)";
    EXPECT_EQ(cheapestWithin(p, 0.01), 2u);
    EXPECT_FALSE(cheapestWithin(p, 0.005));
}

// The oracle's half-width falls as a power of its time: log-log interpolation recovers a point of
// that power law exactly between two of its points.
TEST(Tradeoff, OracleTimeAtAnErrorOnAPowerLaw) {
    std::vector<std::pair<double, double>> curve;
    for (double t : {10.0, 20.0, 40.0, 80.0}) curve.emplace_back(t, 0.5 / std::sqrt(t));
    const double e = 0.5 / std::sqrt(30.0);
    ASSERT_TRUE(oracleMsAtError(curve, e));
    EXPECT_NEAR(*oracleMsAtError(curve, e), 30.0, 1e-9);
    EXPECT_EQ(*oracleMsAtError(curve, 1.0), 10.0) << "met by the first point";
    EXPECT_FALSE(oracleMsAtError(curve, 0.01)) << "the run ended above it";
    EXPECT_FALSE(oracleMsAtError({}, 0.1));
}

}  // namespace
}  // namespace so::test
