#include "oracle/trace_merge_stats.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "core/error.h"

namespace so {

namespace {

// A band's curve at `rounds` packets: its own point there, or, past its last point (every one of
// its pixels had stopped), that last point. Null without a curve.
const CostPoint* curveAt(const AreaShadowStats& s, int rounds) {
    for (const CostPoint& p : s.costCurve)
        if (p.rounds == rounds) return &p;
    if (!s.costCurve.empty() && s.costCurve.back().rounds < rounds) return &s.costCurve.back();
    return nullptr;
}

// The whole image's cost curve: read at the rounds of the band that sampled longest (the whole
// run reads at the same ones), each band's mean weighted by its pixels.
std::vector<CostPoint> mergeCurves(const std::vector<const AreaShadowStats*>& bands,
                                   const std::vector<uint64_t>& penumbraPixels,
                                   uint64_t pixelsSampled) {
    const AreaShadowStats* longest = nullptr;
    for (const AreaShadowStats* b : bands)
        if (!b->costCurve.empty() &&
            (!longest || b->costCurve.back().rounds > longest->costCurve.back().rounds))
            longest = b;
    std::vector<CostPoint> curve;
    if (!longest) return curve;
    uint64_t penumbraTotal = 0;
    for (uint64_t n : penumbraPixels) penumbraTotal += n;
    for (const CostPoint& at : longest->costCurve) {
        CostPoint point{at.rounds, 0, 0.0, std::nullopt};
        double penumbraSum = 0.0;
        for (size_t b = 0; b < bands.size(); ++b) {
            const CostPoint* p = curveAt(*bands[b], at.rounds);
            if (!p) continue;
            point.samples += p->samples;
            point.meanHalfWidth += p->meanHalfWidth * double(bands[b]->pixelsSampled);
            if (p->penumbraMeanHalfWidth)
                penumbraSum += *p->penumbraMeanHalfWidth * double(penumbraPixels[b]);
        }
        point.meanHalfWidth /= double(pixelsSampled);
        if (penumbraTotal) point.penumbraMeanHalfWidth = penumbraSum / double(penumbraTotal);
        curve.push_back(point);
    }
    return curve;
}

// The bands' exact passes: the counts add up; the sum of |V_exact - V| too (the bands' pixels
// are disjoint), so the merged means are the whole run's.
ExactPenumbraStats mergeExact(const std::vector<const AreaShadowStats*>& bands) {
    ExactPenumbraStats total;
    total.method = bands.front()->exact->method;
    total.allPixels = bands.front()->exact->allPixels;
    total.notApplied = bands.front()->exact->notApplied;
    total.errorKind = bands.front()->exact->errorKind;
    total.bound = bands.front()->exact->bound;
    for (const AreaShadowStats* b : bands) {
        const ExactPenumbraStats& e = *b->exact;
        combineStats(total, e);
        for (size_t k = 0; k < total.occluders.size(); ++k) total.occluders[k] += e.occluders[k];
    }
    return total;
}

AreaShadowStats mergeArea(const std::vector<const AreaShadowStats*>& bands,
                          const std::vector<uint64_t>& penumbraPixels) {
    const AreaShadowStats& first = *bands.front();
    AreaShadowStats total;
    total.sampling = first.sampling;
    total.targetError = first.targetError;
    total.agreementTarget = first.agreementTarget;
    total.maxSpp = first.maxSpp;
    double efficiency = 0.0;
    for (const AreaShadowStats* b : bands) {
        combineStats(total, *b);
        efficiency += b->samplingEfficiency * double(b->pixelsSampled);
    }
    if (total.pixelsSampled) {
        total.samplingEfficiency = efficiency / double(total.pixelsSampled);
        total.costCurve = mergeCurves(bands, penumbraPixels, total.pixelsSampled);
    }
    if (std::all_of(bands.begin(), bands.end(),
                    [](const AreaShadowStats* b) { return b->exact.has_value(); }))
        total.exact = mergeExact(bands);
    return total;
}

OracleLightStats mergeLight(const std::vector<TileStats>& tiles, size_t li) {
    const OracleLightStats& first = tiles.front().stats.lights[li];
    OracleLightStats l;
    l.name = first.name;
    l.type = first.type;
    l.method = first.method;
    // Every band probed the same coarse image of the whole view: the same choice; each estimated
    // its own points' seconds, which add up.
    l.choice = first.choice;
    if (l.choice) {
        l.choice->exactSeconds = l.choice->sampledSeconds = 0.0;
        for (const TileStats& t : tiles)
            if (const auto& c = t.stats.lights[li].choice) {
                l.choice->exactSeconds += c->exactSeconds;
                l.choice->sampledSeconds += c->sampledSeconds;
            }
    }
    std::vector<const AreaShadowStats*> areas;
    std::vector<uint64_t> penumbra;
    for (const TileStats& t : tiles) {
        const OracleLightStats& b = t.stats.lights[li];
        if (b.name != first.name || b.area.has_value() != first.area.has_value() ||
            b.hard.has_value() != first.hard.has_value())
            throw std::invalid_argument("mergeTileStats: light " + std::to_string(li) +
                                        " differs between bands (\"" + printable(first.name) +
                                        "\", \"" + printable(b.name) + "\")");
        if (b.area) {
            areas.push_back(&*b.area);
            penumbra.push_back(li < t.penumbraPixels.size() ? t.penumbraPixels[li] : 0);
        }
        if (b.hard) combineStats(l.hard ? *l.hard : l.hard.emplace(), *b.hard);
    }
    if (!areas.empty()) l.area = mergeArea(areas, penumbra);
    return l;
}

}  // namespace

OracleStats mergeTileStats(const std::vector<TileStats>& tiles, int width, int height) {
    if (tiles.empty()) throw std::invalid_argument("mergeTileStats: no bands");
    const OracleStats& first = tiles.front().stats;
    OracleStats s;
    s.width = width;
    s.height = height;
    s.threads = first.threads;
    s.effects = first.effects;
    s.seed = first.seed;
    s.frame = first.frame;
    s.offsetPolicy = first.offsetPolicy;
    s.embree = first.embree;
    s.tbbVersion = first.tbbVersion;
    for (const TileStats& t : tiles) {
        const OracleStats& b = t.stats;
        if (b.lights.size() != first.lights.size())
            throw std::invalid_argument("mergeTileStats: the bands have different light counts (" +
                                        std::to_string(first.lights.size()) + ", " +
                                        std::to_string(b.lights.size()) + ")");
        s.buildBvhSeconds += b.buildBvhSeconds;
        s.primarySeconds += b.primarySeconds;
        s.shadowSeconds += b.shadowSeconds;
        s.shadowRays += b.shadowRays;
        s.closestHitQueries += b.closestHitQueries;
        s.primaryAlphaTests += b.primaryAlphaTests;
        s.shadowAlphaTests += b.shadowAlphaTests;
        s.offsetPolicy.maxBlindDistance =
            std::max(s.offsetPolicy.maxBlindDistance, b.offsetPolicy.maxBlindDistance);
        s.offsetPolicy.maxBlindDistanceRelative = std::max(s.offsetPolicy.maxBlindDistanceRelative,
                                                           b.offsetPolicy.maxBlindDistanceRelative);
    }
    for (size_t li = 0; li < first.lights.size(); ++li) s.lights.push_back(mergeLight(tiles, li));
    return s;
}

}  // namespace so
