#include "raster_compare/compare/sequence_judge.h"

#include <cmath>
#include <limits>
#include <utility>

#include "core/channels.h"

namespace so {

namespace ch = channels;

namespace {

// A sequence's flicker counts a change of V by more than kSequenceFlickerJump, not only a flip.
TemporalOptions flickerOptions() {
    TemporalOptions o;
    o.rasterJump = kSequenceFlickerJump;
    return o;
}

}  // namespace

SequenceJudge::SequenceJudge(std::string light, MetricOptions options)
    : light_(std::move(light)), options_(options) {}

void SequenceJudge::add(const SequenceFrame& in) {
    const TemporalFrame& f = in.frame;
    // The truth's V now, NaN where the oracle missed (no surface to compare with).
    const size_t n = f.oracle->pixelCount();
    const float* vo = f.oracle->channel(ch::lightChannel(light_, ch::kVisibility));
    const float* hit = f.oracle->channel(ch::kHit);
    std::vector<float> now(n);
    for (size_t i = 0; i < n; ++i)
        now[i] = hit[i] != 0.0f ? vo[i] : std::numeric_limits<float>::quiet_NaN();
    std::vector<uint8_t> changed = truthChanged(now);

    MetricOptions options = options_;
    options.truthChanged = &changed;
    ErrorMaps maps;
    const LightMetrics m = computeLightMetrics(*f.oracle, *f.raster, light_, options, &maps);
    metrics_.maePerFrame.push_back(m.mae);
    metrics_.ghostingEligible += m.ghostingEligible;
    metrics_.ghostingPixels += m.ghostingPixels;
    if (previous_)
        metrics_.flicker.add(
            compareFramePair(*previous_, f, light_, flickerOptions(), nullptr, in.motion));
    previous_ = f;

    for (size_t i = 0; i < n; ++i) {
        if (!maps.counted[i] || !changed[i]) continue;
        ++metrics_.lagPixels;
        metrics_.lagAbsSum += double(maps.error[i]);
    }
    metrics_.lastTruthChanged = std::move(changed);
    oracleHistory_.push_back(std::move(now));
    if (oracleHistory_.size() > size_t(kLagFrames)) oracleHistory_.erase(oracleHistory_.begin());
}

std::vector<uint8_t> SequenceJudge::truthChanged(const std::vector<float>& now) const {
    std::vector<uint8_t> changed(now.size(), 0);
    for (const std::vector<float>& before : oracleHistory_) {
        if (before.size() != now.size()) continue;
        // NaN on either side (a miss) compares false: no change.
        for (size_t i = 0; i < now.size(); ++i)
            changed[i] |= uint8_t(std::abs(now[i] - before[i]) > kLagJump);
    }
    return changed;
}

}  // namespace so
