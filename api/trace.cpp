// The API's oracle: runOracle (or runOracleAtPoints) with the trace command's options.
#include <nlohmann/json.hpp>

#include "api/api_internal.h"
#include "core/gbuffer.h"
#include "oracle/oracle.h"
#include "oracle/points.h"

namespace shadow_oracle {

namespace {

so::OracleOptions oracleOptions(const TraceOptions& o) {
    so::OracleOptions out;
    out.width = o.width;
    out.height = o.height;
    out.threads = o.threads;
    out.area.targetError = o.targetError;
    out.area.agreementTarget = o.agreementTarget;
    out.area.maxSpp = o.maxSpp;
    out.area.fixedSpp = o.fixedSpp;
    out.area.seed = o.seed;
    out.verify.pixels = o.verify;
    out.penumbra.method = so::parsePenumbraMethod(o.penumbra, "trace options", "penumbra");
    out.penumbra.allPixels = so::parseExactPixels(o.exactPixels, "trace options", "exact_pixels");
    out.progress = detail::toLibrary(o.progress);
    return out;
}

// The checks the trace command's options get from its parser (cli/main.cpp), as errors here.
void checkOptions(const TraceOptions& o) {
    const auto fail = [](const std::string& field, const std::string& why) {
        so::throwInputError("trace options", field, why);
    };
    if (o.width < 0 || o.width > 16384) fail("width", "must be in [0, 16384]");
    if (o.height < 0 || o.height > 16384) fail("height", "must be in [0, 16384]");
    if (o.threads < 0 || o.threads > 1024) fail("threads", "must be in [0, 1024]");
    if (!(o.targetError >= 1e-4 && o.targetError <= 0.5))
        fail("target_error", "must be in [1e-4, 0.5]");
    if (!(o.agreementTarget >= 1e-4 && o.agreementTarget <= 0.5))
        fail("agreement_target", "must be in [1e-4, 0.5]");
    if (o.maxSpp < 16 || o.maxSpp > (1 << 20)) fail("max_spp", "must be in [16, 1048576]");
    if (o.fixedSpp < 0 || o.fixedSpp > (1 << 20)) fail("spp", "must be in [0, 1048576]");
    if (o.verify < 0 || o.verify > (1 << 20)) fail("verify", "must be in [0, 1048576]");
    if (!o.points.empty() && (o.width > 0 || o.height > 0))
        fail("points", "the image is the G-buffer's size: no width or height with points");
}

}  // namespace

TraceResult trace(const Scene& scene, const TraceOptions& options) {
    return detail::translated([&] {
        checkOptions(options);
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

}  // namespace shadow_oracle
