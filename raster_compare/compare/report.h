// The self-contained HTML report of a comparison: per scene and light the oracle, each technique
// and its error map coloured by class, a sortable table of the metrics, and an accuracy-vs-time
// chart (inline SVG, Pareto front marked). No external file, script or font.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/image.h"
#include "raster_compare/compare/metrics.h"

namespace so {

struct ReportTechnique {
    std::string label;
    std::string family;  // TechniqueInfo::family: the report groups by it
    // Settings that differ only in the technique's quality parameter share `curve` (TradeoffPoint);
    // `quality` is its value, none for a technique without one.
    std::string curve;
    std::optional<double> quality;
    ChannelImage image;                   // raster.exr
    std::vector<LightComparison> lights;  // per light, in scene order
};

struct ReportInput {
    std::string sceneFile;
    std::vector<std::string> lights;
    ChannelImage oracle;
    std::vector<ReportTechnique> techniques;
    nlohmann::json provenance;  // tool, scene hash, GL renderer: shown in the footer
    std::string timedOn;        // the GL renderer that measured the times
    // Per light, sampled area lights only: the oracle's own cost curve, (ms, mean stated 95%
    // half-width over the penumbra's pixels) as its adaptive run went (docs/oracle.md).
    std::vector<std::vector<std::pair<double, double>>> oracleCurves;
};

void writeReport(const std::string& path, const ReportInput& in);

}  // namespace so
