// The trace options: the oracle's option table (core/option_table.h), the single source of their
// validation on every surface (the CLI's options of `trace` and `compare`, the API's checks, the
// sweep spec's oracle keys), of `shadow-oracle trace-options`, of docs/cli.md's table and of the
// oracle cache's key (the rows that change the result). The oracle writes checked values into its
// options (oracle/trace_options.h). The API's struct, the Python keywords and the .pyi stub state
// their defaults in their own language; TraceOptionTable.* and tests/python fail where they differ
// from this table.
#pragma once

#include <cstdint>
#include <span>
#include <string>

#include "core/option_table.h"

namespace so {

// The names the trace options had before the tables were one machinery.
using TraceOptionType = OptionType;
using TraceSurface = OptionSurface;
using TraceOptionValue = OptionValue;
using TraceOptionValues = OptionValues;
using TraceOptionSpec = OptionSpec;
using TraceOptionNaming = OptionNaming;

// Limits the rows use, named once: the largest image side, the default most samples a pixel,
// the most sides of a disk's bounding polygons (oracle/disk_bounds.h's kMaxDiskSides is this).
inline constexpr int kMaxImageSide = 16384;
inline constexpr int kDefaultMaxSpp = kMaxImageSide;
inline constexpr uint32_t kMaxBoundSides = uint32_t(kMaxImageSide);

const OptionTable& traceOptions();
std::span<const TraceOptionSpec> traceOptionTable();
// The row of `key`; std::invalid_argument for a key not in the table (a bug, not input).
const TraceOptionSpec& traceOption(const std::string& key);

inline const char* traceOptionTypeName(TraceOptionType t) {
    return optionTypeName(t);
}
inline void checkTraceOption(const TraceOptionSpec& spec, const TraceOptionValue& v,
                             const std::string& file, const std::string& field,
                             bool allowUnsetZero) {
    checkOption(spec, v, file, field, allowUnsetZero);
}
// Checks each of `values`; std::invalid_argument for a key not in the table.
inline void checkTraceOptions(const TraceOptionValues& values, const TraceOptionNaming& naming) {
    checkOptions(traceOptions(), values, naming);
}
inline std::string traceOptionDefaultText(const TraceOptionSpec& s) {
    return optionDefaultText(s);
}
inline std::string traceOptionHelp(const TraceOptionSpec& s) {
    return optionHelp(s);
}

// The table as Markdown (docs/cli.md, "Trace options") or as JSON (format_version 1).
inline std::string traceOptionsMarkdown() {
    return optionsMarkdown(traceOptions());
}
inline std::string traceOptionsJson() {
    return optionsJson(traceOptions());
}

}  // namespace so
