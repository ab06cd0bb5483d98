// The API's output folders: the files the trace, raster and compare commands write, through the
// same library writers (oracle/trace_output.h, raster_compare/gl/render/raster_output.h,
// raster_compare/pipeline/compare_output.h).
#include "api/api_internal.h"
#include "oracle/trace_output.h"
#include "raster_compare/gl/render/raster_output.h"
#include "raster_compare/pipeline/compare_output.h"

namespace shadow_oracle {

namespace {

// The result's own data, or an Error naming what it should have come from.
template <typename Data>
const Data& dataOf(const std::shared_ptr<const Data>& data, const std::string& what,
                   const std::string& from) {
    if (!data) so::throwInputError(what, "result", "not a result of " + from);
    return *data;
}

std::vector<std::string> withPreviews(std::vector<std::string> paths,
                                      const std::vector<std::string>& previews) {
    paths.insert(paths.end(), previews.begin(), previews.end());
    return paths;
}

}  // namespace

std::vector<std::string> writeTraceOutput(const Scene& scene, const TraceResult& result,
                                          const std::string& outDir, bool previews) {
    return detail::translated([&] {
        const TraceResult::Data& data = dataOf(result.data, "writeTraceOutput", "trace()");
        const so::Scene& s = scene.data().scene;
        if (data.oracle.stats.lights.size() != s.lights.size())
            so::throwInputError("writeTraceOutput", "result",
                                "traced on another scene (other lights)");
        const so::OracleResult r{data.oracle.image, data.oracle.stats, data.points};
        so::TraceOutputOptions output;
        output.scenePath = s.path.string();
        output.loadSeconds = scene.data().loadSeconds;
        output.previews = previews;
        output.frame = scene.data().frame;
        const so::TraceOutputFiles files = so::writeTraceOutput(outDir, s, data.options, r, output);
        return withPreviews({files.exr.string(), files.json.string()}, files.previews);
    });
}

std::vector<std::string> writeRenderOutput(const Scene& scene, const RenderResult& result,
                                           const std::string& outDir, bool previews) {
    return detail::translated([&] {
        const RenderResult::Data& data = dataOf(result.data, "writeRenderOutput", "render()");
        const so::Scene& s = scene.data().scene;
        const so::RasterResult r{data.image, data.stats};
        const so::RasterOutputFiles files =
            so::writeRasterOutput(outDir, s, s.path.string(), data.technique, r, previews);
        return withPreviews({files.exr.string(), files.json.string()}, files.previews);
    });
}

std::vector<std::string> writeCompareOutput(const Scene& scene, const TraceResult& oracle,
                                            const CompareResult& result, const std::string& outDir,
                                            bool report) {
    return detail::translated([&] {
        const CompareResult::Data& data = dataOf(result.data, "writeCompareOutput", "compare()");
        const TraceResult::Data& traced = dataOf(oracle.data, "writeCompareOutput", "trace()");
        const so::Scene& s = scene.data().scene;
        so::CompareOutputOptions output;
        output.scenePath = s.path.string();
        output.boundaryRadius = data.boundaryRadius;
        output.sampling = traced.options.area;
        output.writeReport = report;
        so::Comparison comparison = data.comparison;  // the report takes the rows' images
        const so::CompareOutputFiles files =
            so::writeCompareOutput(outDir, s, traced.oracle, comparison, output);
        std::vector<std::string> paths = {files.metricsJson.string(), files.metricsCsv.string(),
                                          files.metricsWideCsv.string()};
        if (files.report) paths.push_back(files.report->string());
        return paths;
    });
}

}  // namespace shadow_oracle
