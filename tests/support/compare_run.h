// A comparison run from a test as `compare` runs it, quickly (one untimed frame a technique, no
// oracle cache): shared by the pipeline tests of sequences, still frames and ghosting.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "raster_compare/pipeline/compare_scene.h"

namespace so::test {

// The options of `compare SCENE --technique T...`, one untimed frame each, no oracle cache; the
// errors name the options as the test's own words.
inline CompareOptions quickCompareOptions(const std::filesystem::path& scene,
                                          const std::vector<std::string>& techniques) {
    CompareOptions o;
    o.scenePath = scene.string();
    o.techniques = techniques;
    o.useCache = false;
    o.raster.frames = 1;
    o.raster.warmup = 0;
    o.names = {"test",   "technique", "image", "points",   "frames_path",
               "verify", "size",      "out",   "sequence", "converge"};
    return o;
}

// metrics.json of the comparison; where o.outDir is set, its output folder written there too.
inline nlohmann::json compareMetrics(const CompareOptions& o) {
    CompareRun run = compareScene(o);
    // Before the output is written: writing it takes the rows' images.
    const nlohmann::json metrics =
        metricsJson(run.scene, o.scenePath, run.oracle, run.comparison, o.boundaryRadius);
    if (!o.outDir.empty()) writeCompareRun(o, run);
    return metrics;
}

}  // namespace so::test
