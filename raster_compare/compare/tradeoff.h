// Error against cost across the techniques of one light (docs/metrics.md, "Error against cost"):
// the Pareto front, the curves a technique draws over its quality parameter, the cheapest setting
// under an error budget, and what the oracle took to state intervals as small as an error.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace so {

struct TradeoffPoint {
    std::string label;  // as given: "pcss:filter_samples=8"
    // Settings that differ only in their technique's quality parameter share a curve key (the
    // technique's name and its other parameters); `quality` is that parameter's value.
    std::string curve;
    std::optional<double> quality;
    double cost = 0.0;   // the cost: median frame time, or another cost axis (bytes, fragments)
    double error = 0.0;  // mean error against the oracle (which one is the caller's choice)
};

// The points no other point beats in both cost and error (ties in cost: the lower error), by
// cost; each strictly more accurate than the one before.
std::vector<size_t> paretoFront(const std::vector<TradeoffPoint>& points);

struct TradeoffCurve {
    std::string key;
    std::vector<size_t> points;  // by quality, ascending
};
// The curves with at least two points, in the order their first point appears.
std::vector<TradeoffCurve> qualityCurves(const std::vector<TradeoffPoint>& points);

// The cheapest point whose error is at most `budget` (the first of equal costs); none when none is.
std::optional<size_t> cheapestWithin(const std::vector<TradeoffPoint>& points, double budget);
// The budget table that compare's report and the sweep report both draw: per budget, in order,
// cheapestWithin.
std::vector<std::optional<size_t>> cheapestAtBudgets(const std::vector<TradeoffPoint>& points,
                                                     const std::vector<double>& budgets);

// `curve`: the oracle's (ms, stated mean 95% half-width) as its run went, by time. The time at
// which the half-width came down to `error`, interpolated log-log between the points around it;
// the first point's time when that already met it; none when the run ended above it.
std::optional<double> oracleMsAtError(const std::vector<std::pair<double, double>>& curve,
                                      double error);

}  // namespace so
