// The HTML report of a comparison (docs/report.md): per light first a sortable summary of the
// techniques and a chart of error against cost (the error and the cost chosen on the page, Pareto
// front and quality curves drawn), then the images as a grid (rows: techniques; columns: render,
// error maps, worst region) with a zoom view that flips with the oracle; all metrics, and the
// provenance. No network: style and script inline; images embedded or in a folder beside it.
#pragma once

#include <optional>
#include <string>
#include <utility>
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
    std::string fileLabel;   // its folder and files beside the report (compare's --out)
    std::string parameters;  // every parameter "k=v ...", defaults included
    ChannelImage image;      // raster.exr
    std::vector<LightComparison> lights;  // per light, in scene order
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
};

void writeReport(const std::string& path, const ReportInput& in);

}  // namespace so
