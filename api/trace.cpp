// The API's oracle: runOracle (or runOracleAtPoints) with the trace command's options.
#include <nlohmann/json.hpp>

#include "api/api_internal.h"
#include "api/trace_option_fields.h"
#include "core/gbuffer.h"
#include "oracle/oracle.h"
#include "oracle/points.h"
#include "oracle/trace_options.h"

namespace shadow_oracle {

namespace {

// The options, each checked by the trace option table (one line naming its key: "trace options:
// max_spp: must be an integer in [16, 1048576], got 8"), as the oracle's.
so::OracleOptions oracleOptions(const TraceOptions& o) {
    if (!o.points.empty() && (o.width > 0 || o.height > 0))
        so::throwInputError("trace options", "points",
                            "the image is the G-buffer's size: no width or height with points");
    so::OracleOptions out;
    so::applyTraceOptions(detail::traceOptionValues(o),
                          {"trace options", /*cliNames=*/false, "", /*allowUnsetZero=*/true}, out);
    out.progress = detail::toLibrary(o.progress);
    return out;
}

}  // namespace

TraceResult trace(const Scene& scene, const TraceOptions& options) {
    return detail::translated([&] {
        const so::Scene& s = scene.data().scene;
        const so::OracleOptions o = oracleOptions(options);
        so::OracleResult r;
        if (options.points.empty()) {
            r = so::runOracle(s, o);
        } else {
            r = so::runOracleAtPoints(s, so::readGBuffer(options.points), o);
        }
        TraceResult out;
        for (const so::OracleLightStats& l : r.stats.lights) {
            LightStats ls{l.name, so::lightTypeName(l.type), l.seconds(), 0, 0};
            if (l.area) {
                ls.shadowRays = l.area->raysTraced;
                ls.unconvergedPixels = l.area->pixelsUnconverged;
            }
            if (l.hard) ls.shadowRays += l.hard->raysTraced;
            out.lights.push_back(ls);
        }
        out.seconds = r.stats.buildBvhSeconds + r.stats.primarySeconds + r.stats.shadowSeconds;
        out.disagreements = r.stats.disagreements();
        out.statsJson = so::toJson(r.stats).dump();
        auto data = std::make_shared<TraceResult::Data>();
        data->oracle.key = options.points.empty() ? "traced" : "points " + options.points;
        data->oracle.atPoints = !options.points.empty();
        data->oracle.image = r.image;  // compare() measures against this copy
        data->oracle.stats = std::move(r.stats);
        data->options = o;
        data->options.progress = nullptr;  // the caller's callback is not the result's
        data->points = std::move(r.points);
        out.image = detail::toApi(std::move(r.image));
        out.data = std::move(data);
        return out;
    });
}

std::string traceOptionsJson() {
    return so::traceOptionsJson();
}

}  // namespace shadow_oracle
