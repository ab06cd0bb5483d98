// The typed rows every report reads (docs/metrics.md): metrics.json's "results" read back into one
// row per technique setting (or image), its parameters keeping their names and kinds and each
// light's metrics keyed by the metric table (metric_table.h). Compare's report, the sweep report,
// the baseline (gate --baseline) and the index read these rows, so none of them looks a key up in
// JSON, parses a label or maps a method's index back to its name.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "raster_compare/compare/metric_table.h"

namespace so {

class JsonReader;

// One parameter's value as the setting gave it: a number, an integer, or a method's name.
// metrics.json writes a method as its index (an integer); where the row is made, the technique's
// parameter table names it (raster_compare/pipeline/row_parameters.h).
struct ParamValue {
    enum class Kind { Number, Integer, Name };
    Kind kind = Kind::Number;
    double number = 0.0;  // a Name's index (0 for a text that is no method: an image's cost file)
    std::string name;     // a Name's text
    // As a setting writes it: the name, else the shortest text that reads back as the number
    // ("0.1", "2048"), as sweep labels write their values.
    std::string text() const;
    bool operator==(const ParamValue&) const = default;
};
using RowParameters = std::map<std::string, ParamValue>;

// A value of metrics.json's "parameters": integers and other numbers by their JSON type, a string
// as a Name, anything else (an image's cost file may hold it) as a Name of its JSON text.
ParamValue paramValueOfJson(const nlohmann::json& j);

// One light of a row: the metric table's metrics that metrics.json has there.
class LightRow {
  public:
    std::string light;
    // Whether the row has the metric, null or not: the temporal metrics without a camera path, a
    // member of a null group (penumbra_width_error_px on a hard light) or a metric newer than the
    // file are absent.
    bool has(const MetricInfo& m) const { return values_.count(&m) > 0; }
    // The value; none where null or absent. A flag reads as 1 or 0.
    std::optional<double> value(const MetricInfo& m) const;
    // By the table's name; a name missing from the table is a bug (SO_CHECK).
    std::optional<double> value(const std::string& name) const;
    void set(const MetricInfo& m, std::optional<double> v) { values_[&m] = v; }

  private:
    std::map<const MetricInfo*, std::optional<double>> values_;
};

// One technique setting or image of a run: an entry of metrics.json's "results".
struct ResultRow {
    std::string label;         // the setting as given ("pcf:contact=on"); the technique's name
                               // where an old file has no label
    std::string technique;     // its registered name ("pcf"); "external" for an image
    std::string family;        // empty before schema_version 3
    RowParameters parameters;  // every parameter, defaults included; an image's: its cost file's
    std::vector<LightRow> lights;  // in the file's order
    // Whose designs the row grades (metrics.json's "provenance", issue 63): its combined fidelity,
    // "faithful", "variant" or "own" (empty for an image, or a file before it), and each part as
    // "of: fidelity, anchor" with a variant's deviations, one per line (the reports' tooltips).
    std::string fidelity;
    std::string provenanceText;
    // A technique that builds over frames: how many frames built the judged image (metrics.json's
    // "history_frames"; 0: a cold start); none for the other rows and files before it.
    std::optional<int> historyFrames;
    // Whether the reports mark it: a variant or a design of our own under its name.
    bool notFaithful() const { return fidelity == "variant" || fidelity == "own"; }
    const LightRow* light(const std::string& name) const;
};

// One light's metrics object at `field` ("results[2].lights.key"). InputError naming the field
// ("results[2].lights.key.cost.frame_ms") where a group is not an object or a metric is neither a
// number nor null (nor, for a flag, a boolean).
LightRow readLightRow(const nlohmann::json& metrics, const std::string& light, const JsonReader& r,
                      const std::string& field);
// One entry of "results" at `field` ("results[2]"): InputError on a field of the wrong type, or
// when it names neither a label nor a technique.
ResultRow readResultRow(const nlohmann::json& result, const JsonReader& r,
                        const std::string& field);

}  // namespace so
