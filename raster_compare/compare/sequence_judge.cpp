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
    ErrorMaps maps;
    metrics_.maePerFrame.push_back(
        computeLightMetrics(*f.oracle, *f.raster, light_, options_, &maps).mae);
    if (previous_)
        metrics_.flicker.add(
            compareFramePair(*previous_, f, light_, flickerOptions(), nullptr, in.motion));
    previous_ = f;

    // The truth's V now, NaN where the oracle missed (no surface to compare with).
    const size_t n = f.oracle->pixelCount();
    const float* vo = f.oracle->channel(ch::lightChannel(light_, ch::kVisibility));
    const float* hit = f.oracle->channel(ch::kHit);
    std::vector<float> now(n);
    for (size_t i = 0; i < n; ++i)
        now[i] = hit[i] != 0.0f ? vo[i] : std::numeric_limits<float>::quiet_NaN();
    for (size_t i = 0; i < n; ++i) {
        if (!maps.counted[i]) continue;
        bool changed = false;
        for (const std::vector<float>& before : oracleHistory_)
            changed = changed || (before.size() == n && std::abs(now[i] - before[i]) > kLagJump);
        if (!changed) continue;
        ++metrics_.lagPixels;
        metrics_.lagAbsSum += double(maps.error[i]);
    }
    oracleHistory_.push_back(std::move(now));
    if (oracleHistory_.size() > size_t(kLagFrames)) oracleHistory_.erase(oracleHistory_.begin());
}

}  // namespace so
