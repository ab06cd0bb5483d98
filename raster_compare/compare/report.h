// The HTML report of a comparison (docs/report.md): per light first a sortable summary of the
// techniques and a chart of error against cost (the error and the cost chosen on the page, Pareto
// front and quality curves drawn), contact=on against contact=off where both ran
// (contact_pairs.h), then the images as a grid (rows: techniques; columns: render,
// error maps, worst region) with a zoom view that flips with the oracle; in a sequence, each
// technique's error per frame; all metrics, and the
// provenance. No network: style and script inline; images embedded or in a folder beside it.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/image.h"
#include "raster_compare/compare/metrics.h"
#include "raster_compare/compare/result_row.h"

namespace so {

struct ReportTechnique {
    // Its row of metrics.json read back (result_row.h): label, family (the report groups by it),
    // technique, typed parameters, and per light every metric and cost the tables and the chart
    // show.
    ResultRow row;
    // Settings that differ only in the technique's quality parameter share `curve` (TradeoffPoint);
    // `quality` is its value, none for a technique without one.
    std::string curve;
    std::optional<double> quality;
    std::string fileLabel;   // its folder and files beside the report (compare's --out)
    std::string parameters;  // every parameter "k=v ...", defaults included
    ChannelImage image;      // raster.exr
    // Per light, in scene order: what metrics.json does not hold (the error maps the images
    // section draws, the sequence's error per frame).
    std::vector<LightComparison> lights;
};

// compare --frames-path: for one light, the technique with the highest temporal_flicker_rate at
// its worst pair of consecutive frames (the most flickering pixels): both frames' V and the
// oracle's V of the second, and which of its pixels were tracked and which flickered.
struct FlickerStrip {
    std::string technique;  // its label
    int pair = 0;           // frames pair and pair + 1 (from 0)
    double rate = 0.0;      // the technique's temporal_flicker_rate over the whole path
    size_t flickering = 0;  // in this pair
    int width = 0, height = 0;
    std::vector<float> vPrev, vNext, vOracleNext;
    std::vector<uint8_t> mask;  // of frame pair + 1: 1 tracked, 2 flickering (temporal.h)
};

// Where the exact penumbra pass gave a light's V (--penumbra exact or both, docs/oracle.md "Exact
// penumbrae"): what the run spent for V without sampling error at those pixels.
struct OracleExactPoint {
    double ms = 0.0;       // the sampled pass that found the penumbra, plus the exact pass
    double exactMs = 0.0;  // the exact pass alone
    uint64_t pixels = 0;   // pixels whose V it gave
};

struct ReportInput {
    std::string sceneFile;
    std::vector<std::string> lights;
    ChannelImage oracle;
    std::vector<ReportTechnique> techniques;
    // What made the page (tool, git revision, GL renderer, scene hash, oracle options, date), as
    // (name, value) rows of a small table.
    std::vector<std::pair<std::string, std::string>> provenance;
    // Images inside the page as data: URIs (one self-contained file), or PNGs in a folder beside
    // it (REPORT_images/, the default: a page well under 1 MB).
    bool embedImages = false;
    std::string timedOn;  // the GL renderer that measured the times
    // Per light, sampled area lights only: the oracle's own cost curve, (ms, mean stated 95%
    // half-width over the penumbra's pixels) as its adaptive run went (docs/oracle.md).
    std::vector<std::vector<std::pair<double, double>>> oracleCurves;
    std::vector<std::optional<OracleExactPoint>> oracleExact;  // per light, where it applied
    int pathFrames = 0;  // compare --frames-path N: N, else 0 (no temporal metrics)
    std::vector<std::optional<FlickerStrip>> flickerStrips;  // per light when pathFrames > 0
    // compare --sequence: its frames (each technique's LightComparison::sequence has its error per
    // frame, drawn per light), else 0.
    int sequenceFrames = 0;
};

void writeReport(const std::string& path, const ReportInput& in);

// The images section's note on an area light's oracle V: an estimate with a 95% interval where
// it was sampled, V without sampling error where the exact pass gave it (channel `exact`), or
// both, with the pixel counts, so that an exact penumbra is not called an estimate.
std::string oracleCertaintyNote(const ChannelImage& oracle, const std::string& light);

}  // namespace so
