#include "raster_compare/compare/tradeoff.h"

#include <algorithm>
#include <cmath>
#include <map>

namespace so {

std::vector<size_t> paretoFront(const std::vector<TradeoffPoint>& points) {
    std::vector<size_t> order(points.size());
    for (size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) {
        return points[a].cost < points[b].cost ||
               (points[a].cost == points[b].cost && points[a].error < points[b].error);
    });
    std::vector<size_t> front;
    for (size_t i : order)
        if (front.empty() || points[i].error < points[front.back()].error) front.push_back(i);
    return front;
}

std::vector<TradeoffCurve> qualityCurves(const std::vector<TradeoffPoint>& points) {
    std::vector<TradeoffCurve> curves;
    std::map<std::string, size_t> index;
    for (size_t i = 0; i < points.size(); ++i) {
        if (!points[i].quality) continue;
        const auto [it, added] = index.try_emplace(points[i].curve, curves.size());
        if (added) curves.push_back({points[i].curve, {}});
        curves[it->second].points.push_back(i);
    }
    std::vector<TradeoffCurve> kept;
    for (TradeoffCurve& c : curves) {
        if (c.points.size() < 2) continue;
        std::stable_sort(c.points.begin(), c.points.end(), [&](size_t a, size_t b) {
            return *points[a].quality < *points[b].quality;
        });
        kept.push_back(std::move(c));
    }
    return kept;
}

std::optional<size_t> cheapestWithin(const std::vector<TradeoffPoint>& points, double budget) {
    std::optional<size_t> best;
    for (size_t i = 0; i < points.size(); ++i)
        if (points[i].error <= budget && (!best || points[i].cost < points[*best].cost)) best = i;
    return best;
}

std::vector<std::optional<size_t>> cheapestAtBudgets(const std::vector<TradeoffPoint>& points,
                                                     const std::vector<double>& budgets) {
    std::vector<std::optional<size_t>> out;
    for (double budget : budgets) out.push_back(cheapestWithin(points, budget));
    return out;
}

std::optional<double> oracleMsAtError(const std::vector<std::pair<double, double>>& curve,
                                      double error) {
    if (curve.empty() || !(error > 0.0)) return std::nullopt;
    if (curve.front().second <= error) return curve.front().first;
    for (size_t k = 1; k < curve.size(); ++k) {
        const auto [t1, e1] = curve[k];
        if (e1 > error) continue;
        const auto [t0, e0] = curve[k - 1];
        if (!(t0 > 0.0 && t1 > 0.0 && e1 > 0.0) || e0 == e1) return t1;
        // Straight on log-log axes, as the half-width falls as a power of the samples.
        const double f = std::log(e0 / error) / std::log(e0 / e1);
        return t0 * std::pow(t1 / t0, f);
    }
    return std::nullopt;
}

}  // namespace so
