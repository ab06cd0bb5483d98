// The gate (docs/gate.md): limits on the metrics of a compare run, as checks that pass or fail.
// The limits file and metrics.json are read by the command (cli/gate_command.cpp); this evaluates.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "raster_compare/compare/metrics.h"

namespace so {

struct GateCheck {
    std::string scene, light, technique;  // technique: the label as given to compare
    std::string metric;
    double maximum = 0.0;
    std::optional<double> value;  // none: the metric does not apply (null in metrics.json)
    bool failed() const { return value && *value > maximum; }
};

// Every (row, light, metric) a rule of the limits applies to; later rules override earlier ones
// for the same metric. Throws InputError naming the file and field on a malformed limits file, a
// metric name not in the metric table (a misspelled limit must not pass; the nearest names are
// suggested) or a metrics file of another schema.
std::vector<GateCheck> evaluateGate(const nlohmann::json& metrics, const std::string& metricsPath,
                                    const nlohmann::json& limits, const std::string& limitsPath);

// The newest metrics.json schema_version the gate reads (it reads 1 to this).
constexpr int kMaxMetricsSchema = kMetricsSchemaVersion;

// Checks the shape of a metrics.json before it is read (schema_version, results[].lights{} of
// metric objects); throws InputError naming the file and field.
void checkMetricsShape(const nlohmann::json& metrics, const std::string& metricsPath);

// Shell-style pattern with * and ?, matched against the whole text.
bool globMatch(const std::string& pattern, const std::string& text);

}  // namespace so
