#include "raster_compare/pipeline/sweep_settings.h"

#include <utility>

#include "core/compare_option_table.h"
#include "core/error.h"
#include "core/raster_option_table.h"
#include "core/trace_option_table.h"

namespace so::sweep_detail {
namespace {

// The image size lies at the spec's top level; the other trace options in its "oracle" block.
bool topLevelTraceOption(const std::string& key) {
    return key == "width" || key == "height";
}

// The spec's oracle block: the trace options the table offers to sweeps, with their ranges.
void parseOracle(const Json& o, const std::string& file, SweepOracleSettings& oracle) {
    std::set<std::string> keys;
    for (const TraceOptionSpec& spec : traceOptionTable())
        if ((spec.surfaces & kSurfaceSweep) && !topLevelTraceOption(spec.key))
            keys.insert(spec.key);
    checkKeys(o, keys, file, "oracle");
    for (const auto& [key, value] : o.items())
        oracle.values[key] = optionValue(traceOption(key), value, file, "oracle." + key);
}

// Whether the spec asks for the option: given, and for a flag `true`.
bool asks(const OptionTable& table, const OptionValues& values, const std::string& key) {
    const auto it = values.find(key);
    return it != values.end() &&
           (table.at(key).type != OptionType::Flag || it->second.number != 0.0);
}

// The table's exclusions (OptionSpec::excludes, the command line's), by the spec's keys:
// "converge": 8 with "sequence": true is one or the other.
void checkExclusions(const OptionTable& table, const OptionValues& values,
                     const std::string& file) {
    for (const auto& [key, value] : values)
        for (const std::string& other : table.at(key).excludes)
            if (asks(table, values, key) && asks(table, values, other))
                throwInputError(file, key, "not with " + other + ": one or the other");
}

}  // namespace

std::set<std::string> topLevelKeys() {
    std::set<std::string> keys = {"sweep_format", "name",   "scenes",     "width", "height",
                                  "keep_outputs", "oracle", "techniques", "images"};
    for (const OptionTable* table : {&rasterOptionTable(), &compareOptionTable()})
        for (const OptionSpec& spec : table->rows)
            if (spec.surfaces & kSurfaceSweep) keys.insert(spec.key);
    return keys;
}

SweepSettings parseSettings(const Json& spec, const std::string& file) {
    SweepSettings s;
    if (spec.contains("width"))
        s.oracle.width =
            int(optionValue(traceOption("width"), spec["width"], file, "width").number);
    if (spec.contains("height"))
        s.oracle.height =
            int(optionValue(traceOption("height"), spec["height"], file, "height").number);
    for (const auto& [table, values] :
         {std::pair{&rasterOptionTable(), &s.raster}, std::pair{&compareOptionTable(), &s.compare}})
        for (const OptionSpec& row : table->rows)
            if ((row.surfaces & kSurfaceSweep) && spec.contains(row.key))
                (*values)[row.key] = optionValue(row, spec[row.key], file, row.key);
    checkExclusions(compareOptionTable(), s.compare, file);
    checkExclusions(rasterOptionTable(), s.raster, file);
    if (spec.contains("keep_outputs"))
        s.keepOutputs = boolean(spec["keep_outputs"], file, "keep_outputs");
    if (spec.contains("oracle")) parseOracle(spec["oracle"], file, s.oracle);
    return s;
}

}  // namespace so::sweep_detail
