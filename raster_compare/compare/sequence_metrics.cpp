#include "raster_compare/compare/sequence_metrics.h"

#include <numeric>

namespace so {

double SequenceMetrics::maeMean() const {
    if (maePerFrame.empty()) return 0.0;
    return std::accumulate(maePerFrame.begin(), maePerFrame.end(), 0.0) /
           double(maePerFrame.size());
}

double SequenceMetrics::maeLast() const {
    return maePerFrame.empty() ? 0.0 : maePerFrame.back();
}

std::optional<double> SequenceMetrics::lagMae() const {
    if (lagPixels == 0) return std::nullopt;
    return lagAbsSum / double(lagPixels);
}

std::optional<double> SequenceMetrics::ghostingRate() const {
    if (ghostingEligible == 0) return std::nullopt;
    return double(ghostingPixels) / double(ghostingEligible);
}

nlohmann::json SequenceMetrics::toJson() const {
    const auto opt = [](const std::optional<double>& v) {
        return v ? nlohmann::json(*v) : nlohmann::json(nullptr);
    };
    return {{"frames", frames()},
            {"mae_per_frame", maePerFrame},
            {"mae_mean", maeMean()},
            {"mae_last", maeLast()},
            {"flicker_rate", opt(flicker.rate())},
            {"tracked_pairs", flicker.tracked},
            {"flickering_pairs", flicker.flickering},
            {"lag_mae", opt(lagMae())},
            {"lag_pixels", lagPixels},
            {"ghosting_rate", opt(ghostingRate())},
            {"ghosting_pixels", ghostingPixels}};
}

}  // namespace so
