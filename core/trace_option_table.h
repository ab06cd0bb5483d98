// The trace options: one table (name on the command line, name in the API, Python and the sweep
// spec, type, default, range, meaning, which surfaces carry it) that is the single source of their
// validation on every surface (the CLI's options of `trace` and `compare`, the API's checks, the
// sweep spec's oracle keys), of `shadow-oracle trace-options` and of docs/cli.md's table. The
// oracle writes checked values into its options (oracle/trace_options.h). The API's struct, the
// Python keywords and the .pyi stub state their defaults in their own language; TraceOptionTable.*
// and tests/python fail where they differ from this table. A technique's parameters have the same
// kind of table (raster_compare/gl/params.h). In core, without the oracle, so that the sweep spec
// reader needs only so_core.
#pragma once

#include <map>
#include <span>
#include <string>
#include <vector>

namespace so {

enum class TraceOptionType : unsigned char {
    Integer,
    Real,
    Name,  // picks a method: one of `names`
};
const char* traceOptionTypeName(TraceOptionType t);  // "integer", "real", "name"

// Where an option is offered (bits of TraceOptionSpec::surfaces).
enum TraceSurface : unsigned {
    kSurfaceTrace = 1u << 0,    // `shadow-oracle trace`
    kSurfaceCompare = 1u << 1,  // `shadow-oracle compare`
    kSurfaceSweep = 1u << 2,    // the sweep spec's "oracle" block (width, height: its top level)
    kSurfaceApi = 1u << 3,      // shadow_oracle::TraceOptions and Python's trace() keywords
};

// A value as a surface gives it: a number, or the text of a name.
struct TraceOptionValue {
    double number = 0.0;
    std::string text;
};
using TraceOptionValues = std::map<std::string, TraceOptionValue>;  // by key

struct TraceOptionSpec {
    std::string cli;  // "--target-error"
    std::string key;  // "target_error": the API's and Python's keyword, the sweep spec's key
    TraceOptionType type = TraceOptionType::Integer;
    TraceOptionValue defaultValue;
    // Integer and Real: the range a given value must lie in. `unsetZero`: 0 is allowed too where
    // a surface cannot leave the option out (the API's struct), meaning the default.
    double min = 0.0, max = 0.0;
    bool unsetZero = false;
    bool powerOfTwo = false;
    std::vector<std::string> names;  // Name: the methods, in their order
    std::string defaultText;         // the default as the docs say it, when 0 means something
    std::string help;                // one line for --help
    std::string doc;                 // docs/cli.md's meaning (Markdown)
    std::vector<std::string> excludes = {};  // keys it cannot be given with (command line)
    unsigned surfaces = 0;
};

std::span<const TraceOptionSpec> traceOptionTable();
// The row of `key`; std::invalid_argument for a key not in the table (a bug, not input).
const TraceOptionSpec& traceOption(const std::string& key);

// Throws InputError(file, field, why) unless `v` is valid for `spec`: in range, an integer, a
// power of two, or one of its names ("\"x\" is not penumbra or all"; `allowUnsetZero` where the
// surface gives 0 for the default).
void checkTraceOption(const TraceOptionSpec& spec, const TraceOptionValue& v,
                      const std::string& file, const std::string& field, bool allowUnsetZero);

// How a surface names fields in its errors: the command line's "--bound-max-sides", the API's
// "bound_max_sides", the sweep spec's "oracle.bound_max_sides".
struct TraceOptionNaming {
    std::string file;
    bool cliNames = false;
    std::string prefix;
    bool allowUnsetZero = false;
    std::string field(const TraceOptionSpec& spec) const {
        return cliNames ? spec.cli : prefix + spec.key;
    }
};

// Checks each of `values`; std::invalid_argument for a key not in the table.
void checkTraceOptions(const TraceOptionValues& values, const TraceOptionNaming& naming);

// The default as the docs say it ("0.01", "the scene camera's"), and the --help line with it.
std::string traceOptionDefaultText(const TraceOptionSpec& spec);
std::string traceOptionHelp(const TraceOptionSpec& spec);

// The table as Markdown (docs/cli.md, "Trace options") or as JSON (format_version 1).
std::string traceOptionsMarkdown();
std::string traceOptionsJson();

}  // namespace so
