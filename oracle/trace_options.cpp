#include "oracle/trace_options.h"

#include <map>

#include "oracle/exact_penumbra.h"

namespace so {

namespace {

using Setter = void (*)(OracleOptions& o, const TraceOptionValue& v, const std::string& file,
                        const std::string& field);

// Where each key goes; the names go through the oracle's own parsers.
const std::map<std::string, Setter>& setters() {
    using O = OracleOptions;
    using V = TraceOptionValue;
    using S = std::string;
    static const std::map<std::string, Setter> kSetters = {
        {"width", [](O& o, const V& v, const S&, const S&) { o.width = int(v.number); }},
        {"height", [](O& o, const V& v, const S&, const S&) { o.height = int(v.number); }},
        {"threads", [](O& o, const V& v, const S&, const S&) { o.threads = int(v.number); }},
        {"seed", [](O& o, const V& v, const S&, const S&) { o.area.seed = uint32_t(v.number); }},
        {"target_error",
         [](O& o, const V& v, const S&, const S&) { o.area.targetError = v.number; }},
        {"agreement_target",
         [](O& o, const V& v, const S&, const S&) { o.area.agreementTarget = v.number; }},
        {"max_spp", [](O& o, const V& v, const S&, const S&) { o.area.maxSpp = int(v.number); }},
        {"spp", [](O& o, const V& v, const S&, const S&) { o.area.fixedSpp = int(v.number); }},
        {"verify", [](O& o, const V& v, const S&, const S&) { o.verify.pixels = int(v.number); }},
        {"verify_samples",
         [](O& o, const V& v, const S&, const S&) { o.verify.areaSamples = int(v.number); }},
        {"penumbra",
         [](O& o, const V& v, const S& file, const S& field) {
             o.penumbra.method = parsePenumbraMethod(v.text, file, field);
         }},
        {"exact_pixels",
         [](O& o, const V& v, const S& file, const S& field) {
             o.penumbra.allPixels = parseExactPixels(v.text, file, field);
         }},
        {"bound_target",
         [](O& o, const V& v, const S&, const S&) { o.penumbra.bound.targetHalfWidth = v.number; }},
        {"bound_max_sides", [](O& o, const V& v, const S&,
                               const S&) { o.penumbra.bound.maxSides = uint32_t(v.number); }},
    };
    return kSetters;
}

}  // namespace

void applyTraceOptions(const TraceOptionValues& values, const TraceOptionNaming& naming,
                       OracleOptions& o) {
    checkTraceOptions(values, naming);
    for (const auto& [key, value] : values) {
        const TraceOptionSpec& spec = traceOption(key);
        if (naming.allowUnsetZero && spec.unsetZero && value.number == 0.0) continue;
        setters().at(key)(o, value, naming.file, naming.field(spec));
    }
}

OracleOptions tableDefaultOracleOptions() {
    OracleOptions o;
    for (const TraceOptionSpec& spec : traceOptionTable())
        setters().at(spec.key)(o, spec.defaultValue, "trace option table", spec.key);
    return o;
}

std::vector<std::string> appliedTraceOptionKeys() {
    std::vector<std::string> keys;
    for (const auto& [key, setter] : setters()) keys.push_back(key);
    return keys;
}

}  // namespace so
