#include "oracle/trace_options.h"

#include <cstdint>
#include <map>

#include "oracle/exact_penumbra.h"

namespace so {

namespace {

using Setter = void (*)(OracleOptions& o, const TraceOptionValue& v, const std::string& file,
                        const std::string& field);
// The value back, as the row gives it; the image size is the camera's (the scene camera's where
// the options leave it 0).
using Getter = TraceOptionValue (*)(const OracleOptions& o, const CameraDesc& cam);
struct Field {
    Setter set;
    Getter get;
};

TraceOptionValue number(double v) {
    return {v, ""};
}

// Where each key goes; the names go through the oracle's own parsers.
const std::map<std::string, Field>& fields() {
    using O = OracleOptions;
    using V = TraceOptionValue;
    using S = std::string;
    using C = CameraDesc;
    static const std::map<std::string, Field> kFields = {
        {"width",
         {[](O& o, const V& v, const S&, const S&) { o.width = int(v.number); },
          [](const O&, const C& c) { return number(c.width); }}},
        {"height",
         {[](O& o, const V& v, const S&, const S&) { o.height = int(v.number); },
          [](const O&, const C& c) { return number(c.height); }}},
        {"threads",
         {[](O& o, const V& v, const S&, const S&) { o.threads = int(v.number); },
          [](const O& o, const C&) { return number(o.threads); }}},
        {"seed",
         {[](O& o, const V& v, const S&, const S&) { o.area.seed = uint32_t(v.number); },
          [](const O& o, const C&) { return number(o.area.seed); }}},
        {"target_error",
         {[](O& o, const V& v, const S&, const S&) { o.area.targetError = v.number; },
          [](const O& o, const C&) { return number(o.area.targetError); }}},
        {"agreement_target",
         {[](O& o, const V& v, const S&, const S&) { o.area.agreementTarget = v.number; },
          [](const O& o, const C&) { return number(o.area.agreementTarget); }}},
        {"max_spp",
         {[](O& o, const V& v, const S&, const S&) { o.area.maxSpp = int(v.number); },
          [](const O& o, const C&) { return number(o.area.maxSpp); }}},
        {"spp",
         {[](O& o, const V& v, const S&, const S&) { o.area.fixedSpp = int(v.number); },
          [](const O& o, const C&) { return number(o.area.fixedSpp); }}},
        {"verify",
         {[](O& o, const V& v, const S&, const S&) { o.verify.pixels = int(v.number); },
          [](const O& o, const C&) { return number(o.verify.pixels); }}},
        {"verify_samples",
         {[](O& o, const V& v, const S&, const S&) { o.verify.areaSamples = int(v.number); },
          [](const O& o, const C&) { return number(o.verify.areaSamples); }}},
        {"penumbra",
         {[](O& o, const V& v, const S& file, const S& field) {
              o.penumbra.method = parsePenumbraMethod(v.text, file, field);
          },
          [](const O& o, const C&) {
              return V{0.0, penumbraMethodName(o.penumbra.method)};
          }}},
        {"exact_pixels",
         {[](O& o, const V& v, const S& file, const S& field) {
              o.penumbra.allPixels = parseExactPixels(v.text, file, field);
          },
          [](const O& o, const C&) {
              return V{0.0, o.penumbra.allPixels ? "all" : "penumbra"};
          }}},
        {"bound_target",
         {[](O& o, const V& v, const S&, const S&) { o.penumbra.bound.targetHalfWidth = v.number; },
          [](const O& o, const C&) { return number(o.penumbra.bound.targetHalfWidth); }}},
        {"bound_max_sides",
         {[](O& o, const V& v, const S&, const S&) {
              o.penumbra.bound.maxSides = uint32_t(v.number);
          },
          [](const O& o, const C&) { return number(o.penumbra.bound.maxSides); }}},
    };
    return kFields;
}

}  // namespace

void applyTraceOptions(const TraceOptionValues& values, const TraceOptionNaming& naming,
                       OracleOptions& o) {
    checkTraceOptions(values, naming);
    for (const auto& [key, value] : values) {
        const TraceOptionSpec& spec = traceOption(key);
        if (naming.allowUnsetZero && spec.unsetZero && value.number == 0.0) continue;
        fields().at(key).set(o, value, naming.file, naming.field(spec));
    }
}

OracleOptions tableDefaultOracleOptions() {
    OracleOptions o;
    for (const TraceOptionSpec& spec : traceOptionTable())
        fields().at(spec.key).set(o, spec.defaultValue, "trace option table", spec.key);
    return o;
}

std::vector<std::string> appliedTraceOptionKeys() {
    std::vector<std::string> keys;
    for (const auto& [key, field] : fields()) keys.push_back(key);
    return keys;
}

TraceOptionValue traceOptionValueOf(const OracleOptions& o, const CameraDesc& cam,
                                    const std::string& key) {
    return fields().at(key).get(o, cam);
}

nlohmann::json resultOptionsJson(const OracleOptions& o, const CameraDesc& cam) {
    nlohmann::json j = nlohmann::json::object();
    for (const TraceOptionSpec& spec : traceOptionTable()) {
        if (!spec.changesResult) continue;
        const TraceOptionValue v = traceOptionValueOf(o, cam, spec.key);
        if (spec.type == OptionType::Name)
            j[spec.key] = v.text;
        else if (spec.type == OptionType::Integer)
            j[spec.key] = int64_t(v.number);
        else
            j[spec.key] = v.number;
    }
    return j;
}

}  // namespace so
