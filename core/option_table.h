// An option table: the rows (name on the command line, name in the API, Python and the sweep spec,
// type, default, range, meaning, which surfaces carry it) that are the single source of an option
// kind's validation on every surface, of its listing command (`trace-options`, `raster-options`,
// `compare-options`) and of its table in docs/cli.md. One table per kind, each in its own file:
// the trace options (trace_option_table.h), the raster options (raster_option_table.h), the
// comparison options (compare_option_table.h). A technique's parameters have the same kind of
// table (raster_compare/gl/params.h). In core, so that the sweep spec reader needs only so_core.
#pragma once

#include <map>
#include <span>
#include <string>
#include <vector>

namespace so {

enum class OptionType : unsigned char {
    Integer,
    Real,
    Name,  // picks a method: one of `names`
    Flag,  // on (1) or off (0): a command-line flag without a value
};
const char* optionTypeName(OptionType t);  // "integer", "real", "name", "flag"

// Where an option is offered (bits of OptionSpec::surfaces).
enum OptionSurface : unsigned {
    kSurfaceTrace = 1u << 0,    // `shadow-oracle trace`
    kSurfaceCompare = 1u << 1,  // `shadow-oracle compare`
    kSurfaceSweep = 1u << 2,    // the sweep spec (its top level, or its "oracle" block)
    kSurfaceApi = 1u << 3,      // the public API's option structs and Python's keywords
    kSurfaceRaster = 1u << 4,   // `shadow-oracle raster`
};

// A value as a surface gives it: a number, or the text of a name.
struct OptionValue {
    double number = 0.0;
    std::string text;
};
using OptionValues = std::map<std::string, OptionValue>;  // by key

struct OptionSpec {
    std::string cli;  // "--target-error"
    std::string key;  // "target_error": the API's and Python's keyword, the sweep spec's key
    OptionType type = OptionType::Integer;
    OptionValue defaultValue;
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
    // The option may change what is computed, not only how fast: a trace option so marked is part
    // of the oracle cache's key and of oracle.json's "options" (oracle/oracle_cache.h). True unless
    // a row says otherwise (sameResult), so that a row added without a thought costs a cache miss,
    // never a stale oracle.
    bool changesResult = true;
};

// A kind's rows and what its errors call it ("trace option").
struct OptionTable {
    const char* kind;
    std::span<const OptionSpec> rows;
    // The row of `key`; std::invalid_argument for a key not in the table (a bug, not input).
    const OptionSpec& at(const std::string& key) const;
};

// Rows by their kind: the command-line name is the key's ("max_spp": "--max-spp").
OptionSpec integerOption(const std::string& key, double def, double min, double max,
                         unsigned surfaces, std::string help, std::string doc);
OptionSpec realOption(const std::string& key, double def, double min, double max, unsigned surfaces,
                      std::string help, std::string doc);
// Off by default; the command line gives it as a bare flag.
OptionSpec flagOption(const std::string& key, unsigned surfaces, std::string help, std::string doc);
OptionSpec nameOption(const std::string& key, const std::string& def,
                      std::vector<std::string> names, unsigned surfaces, std::string help,
                      std::string doc);
// Where a surface must give a value (the API's struct), 0 stands for the default `text`.
OptionSpec zeroMeans(OptionSpec s, std::string text);
// The row, marked as leaving the result as it is (threads: bit-identical for any N).
OptionSpec sameResult(OptionSpec s);

// Throws InputError(file, field, why) unless `v` is valid for `spec`: in range, an integer, a
// power of two, or one of its names ("unknown value \"x\" (valid: penumbra, all)";
// `allowUnsetZero` where the surface gives 0 for the default).
void checkOption(const OptionSpec& spec, const OptionValue& v, const std::string& file,
                 const std::string& field, bool allowUnsetZero);

// How a surface names fields in its errors: the command line's "--bound-max-sides", the API's
// "bound_max_sides", the sweep spec's "oracle.bound_max_sides". The caller says which.
struct OptionNaming {
    std::string file;
    bool cliNames = false;
    std::string prefix;
    bool allowUnsetZero = false;
    std::string field(const OptionSpec& spec) const {
        return cliNames ? spec.cli : prefix + spec.key;
    }
};

// Checks each of `values`; std::invalid_argument for a key not in the table.
void checkOptions(const OptionTable& table, const OptionValues& values, const OptionNaming& naming);

// The default as the docs say it ("0.01", "the scene camera's"), and the --help line with it.
std::string optionDefaultText(const OptionSpec& spec);
std::string optionHelp(const OptionSpec& spec);

// The table as Markdown (docs/cli.md) or as JSON (format_version 1).
std::string optionsMarkdown(const OptionTable& table);
std::string optionsJson(const OptionTable& table);

}  // namespace so
