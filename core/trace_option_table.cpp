#include "core/trace_option_table.h"

#include <cmath>
#include <cstdio>
#include <sstream>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "core/error.h"

namespace so {

namespace {

constexpr unsigned kAll = kSurfaceTrace | kSurfaceCompare | kSurfaceSweep | kSurfaceApi;
constexpr double kMaxSamples = 1 << 20;

// A row by its kind: the command-line name is the key's ("max_spp": "--max-spp").
TraceOptionSpec numberOption(TraceOptionType type, const std::string& key, double def, double min,
                             double max, unsigned surfaces, std::string help, std::string doc) {
    TraceOptionSpec s;
    s.cli = "--";
    for (char c : key) s.cli += c == '_' ? '-' : c;
    s.key = key;
    s.type = type;
    s.defaultValue = {def, ""};
    s.min = min;
    s.max = max;
    s.surfaces = surfaces;
    s.help = std::move(help);
    s.doc = std::move(doc);
    return s;
}
TraceOptionSpec integer(const std::string& key, double def, double min, double max,
                        unsigned surfaces, std::string help, std::string doc) {
    return numberOption(TraceOptionType::Integer, key, def, min, max, surfaces, std::move(help),
                        std::move(doc));
}
TraceOptionSpec real(const std::string& key, double def, double min, double max, unsigned surfaces,
                     std::string help, std::string doc) {
    return numberOption(TraceOptionType::Real, key, def, min, max, surfaces, std::move(help),
                        std::move(doc));
}
TraceOptionSpec method(const std::string& key, const std::string& def,
                       std::vector<std::string> names, unsigned surfaces, std::string help,
                       std::string doc) {
    TraceOptionSpec s = numberOption(TraceOptionType::Name, key, 0, 0, 0, surfaces, std::move(help),
                                     std::move(doc));
    s.defaultValue = {0.0, def};
    s.names = std::move(names);
    return s;
}
// Where a surface must give a value (the API's struct), 0 stands for the default `text`.
TraceOptionSpec zeroMeans(TraceOptionSpec s, std::string text) {
    s.unsetZero = true;
    s.defaultText = std::move(text);
    return s;
}

constexpr unsigned kCli = kSurfaceTrace | kSurfaceCompare;
constexpr unsigned kNoCompare = kSurfaceTrace | kSurfaceSweep | kSurfaceApi;

// The rows, in the order of docs/cli.md. A default is stated once, here; a change of one is a
// change of this line (and of the API's and Python's spelling of it, which the tests compare).
std::vector<TraceOptionSpec> makeTable() {
    std::vector<TraceOptionSpec> t;
    t.push_back(zeroMeans(integer("width", 0, 1, 16384, kAll, "image width",
                                  "image width; the field of view stays vertical"),
                          "the scene camera's"));
    t.push_back(zeroMeans(integer("height", 0, 1, 16384, kAll, "image height", "image height"),
                          "the scene camera's"));
    t.push_back(zeroMeans(integer("threads", 0, 1, 1024, kCli | kSurfaceApi, "worker threads",
                                  "threads for tracing; the output is bit-identical for any N"),
                          "all cores"));
    t.push_back(integer("seed", 0, 0, 4294967295.0, kAll, "seed of the area-light sample sequences",
                        "seed of the area-light sample sequences; the output is a function of "
                        "the scene, the options and the seed only"));
    t.push_back(real("target_error", 0.01, 1e-4, 0.5, kAll,
                     "area lights: stop a pixel when its 95% half-width is below this",
                     "area lights (`penumbra`): a pixel stops sampling when the half-width of its "
                     "95% interval is at most E"));
    t.push_back(real("agreement_target", 0.01, 1e-4, 0.5, kAll,
                     "area lights: a pixel whose samples all agree (lit, or umbra) stops at the "
                     "larger of this and --target-error (docs/oracle.md)",
                     "area lights: a pixel whose samples all agree (all lit, or all shadowed) "
                     "stops when its half-width, which only the prior sets there, is at most the "
                     "larger of A and E ([oracle.md](oracle.md), stopping rule)"));
    t.push_back(integer("max_spp", 16384, 16, kMaxSamples, kNoCompare,
                        "area lights: most samples per pixel",
                        "area lights: the most samples a pixel may take"));
    t.push_back(zeroMeans(
        integer("spp", 0, 1, kMaxSamples, kNoCompare,
                "area lights: exactly this many samples per pixel (no adaptivity)",
                "area lights: exactly N samples per pixel instead, rounded up to a multiple of 16"),
        "adaptive"));
    t.back().excludes = {"target_error", "agreement_target", "max_spp"};
    t.push_back(integer("verify", 0, 0, kMaxSamples, kCli | kSurfaceApi,
                        "re-trace N random pixels per light (plus up to N near the horizon) with "
                        "an independent exact tracer; exit 3 on any disagreement",
                        "re-trace N random pixels per light, plus up to N whose light is within 3 "
                        "degrees of the horizon, with an independent exact tracer "
                        "([oracle.md](oracle.md#verification)); prints a summary line; exit 3 on "
                        "any disagreement. Part of the cache key (`compare`)"));
    t.back().defaultText = "0 (off)";
    t.push_back(integer("verify_samples", 4096, 64, kMaxSamples, kSurfaceTrace,
                        "reference samples per area-light pixel checked",
                        "reference samples per checked pixel of a sampled area light"));
    t.push_back(method(
        "penumbra", "auto", {"sampled", "exact", "both", "auto"}, kAll,
        "auto (per light, exact or sampled, whichever a probe estimates cheaper), sampled (RQMC "
        "with 95% intervals), exact (rect and polygon lights: clipped polygons on every pixel, "
        "stderr 0 there; disk and sphere lights: with a stated error, NAME.bound) or both "
        "(V sampled, V_exact beside it)",
        "area lights with the `penumbra` effect: `auto` (per light, `exact` or `sampled`, "
        "whichever a probe of one pixel in 64 estimates cheaper at the requested target, exact "
        "unless its estimate is over 1.5 times sampling's; oracle.json's `penumbra_choice` says "
        "which and why), `sampled` (RQMC with 95% intervals), `exact` (every pixel without "
        "sampling, stderr 0, `NAME.exact` 1: rect and polygon lights exact by clipping, disk and "
        "sphere lights by clipping and integrating arcs, their stated error in `NAME.bound`; the "
        "exact pass finds its own pixels and no sampled pass runs except on the pixels it cannot "
        "answer, too many occluders or an alpha-tested triangle in the pyramid) or `both` (V stays "
        "sampled; `NAME.V_exact` beside it and their disagreement in oracle.json); "
        "[oracle.md](oracle.md#exact-penumbrae). Part of the cache key (`compare`)"));
    t.push_back(method("exact_pixels", "penumbra", {"penumbra", "all"}, kAll,
                       "with --penumbra both: penumbra (pixels whose samples disagree) or all "
                       "(every sampled pixel); exact finds its own pixels",
                       "with `--penumbra both`: `penumbra` (pixels whose samples disagreed) or "
                       "`all` (every sampled pixel: a small occluder no sample met is found too). "
                       "`exact` needs no choice: it computes every pixel"));
    t.push_back(real("bound_target", 1e-6, 1e-7, 0.5, kAll,
                     "disk and sphere lights with --penumbra exact, both or auto: the stated "
                     "error above which a pixel counts as missing its target",
                     "disk and sphere lights with `--penumbra exact`, `both` or `auto` (where it "
                     "chose exact): a pixel whose stated error (`NAME.bound`, about 1e-8) is above "
                     "it counts in `exact_penumbra.bound.pixels_target_missed` "
                     "([oracle.md](oracle.md#disk-and-sphere-lights))"));
    // The range is oracle/disk_bounds.h's (DiskBoundOptions::minSides, kMaxDiskSides), which
    // TraceOptionTable.* holds to this.
    t.push_back(integer("bound_max_sides", 4096, 32, 16384, kAll,
                        "the most sides of the polygons bounding a disk (the independent check, "
                        "not the exact pass), a power of two in [32, 16384]",
                        "the most sides of the polygons that bound a disk "
                        "(`oracle/disk_bounds.h`: the exact pass's independent check in the "
                        "tests; the exact pass itself does not use it)"));
    t.back().powerOfTwo = true;
    return t;
}

// Bounds as the errors and the docs write them: 0.0001, 1048576.
std::string numberText(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.12g", v);
    return buf;
}

// Bounds as docs/cli.md writes them: 2^20 rather than 1048576.
std::string docNumber(double v) {
    for (int k = 16; k <= 32; ++k) {
        if (v == std::ldexp(1.0, k)) return "2^" + std::to_string(k);
        if (v == std::ldexp(1.0, k) - 1) return "2^" + std::to_string(k) + " - 1";
    }
    return numberText(v);
}

std::string valueText(const TraceOptionSpec& s, const TraceOptionValue& v) {
    return s.type == TraceOptionType::Name ? v.text : numberText(v.number);
}

// The surfaces by their names in traceOptionsJson, in the docs' order.
constexpr std::pair<unsigned, const char*> kSurfaceNames[] = {{kSurfaceTrace, "trace"},
                                                              {kSurfaceCompare, "compare"},
                                                              {kSurfaceSweep, "sweep"},
                                                              {kSurfaceApi, "api"}};

}  // namespace

const char* traceOptionTypeName(TraceOptionType t) {
    switch (t) {
        case TraceOptionType::Integer:
            return "integer";
        case TraceOptionType::Real:
            return "real";
        case TraceOptionType::Name:
            return "name";
    }
    return "?";
}

std::span<const TraceOptionSpec> traceOptionTable() {
    static const std::vector<TraceOptionSpec> table = makeTable();
    return table;
}

const TraceOptionSpec& traceOption(const std::string& key) {
    for (const TraceOptionSpec& s : traceOptionTable())
        if (s.key == key) return s;
    throw std::invalid_argument("no trace option " + key);
}

void checkTraceOption(const TraceOptionSpec& spec, const TraceOptionValue& v,
                      const std::string& file, const std::string& field, bool allowUnsetZero) {
    if (spec.type == TraceOptionType::Name) {
        for (const std::string& n : spec.names)
            if (v.text == n) return;
        // "penumbra or all"; "a method (sampled, exact, both or auto)"
        std::string list;
        for (size_t k = 0; k < spec.names.size(); ++k)
            list += (k == 0 ? "" : k + 1 == spec.names.size() ? " or " : ", ") + spec.names[k];
        throwInputError(file, field,
                        "\"" + printable(v.text, 40) + "\" is not " +
                            (spec.names.size() > 2 ? "a method (" + list + ")" : list));
    }
    const double x = v.number;
    if (allowUnsetZero && spec.unsetZero && x == 0.0) return;
    const bool integer = spec.type == TraceOptionType::Integer;
    const std::string range = "[" + numberText(spec.min) + ", " + numberText(spec.max) + "]";
    if (spec.powerOfTwo) {
        const bool ok = x >= spec.min && x <= spec.max && x == std::floor(x) &&
                        (uint64_t(x) & (uint64_t(x) - 1)) == 0;
        if (!ok) throwInputError(file, field, numberText(x) + " is not a power of two in " + range);
        return;
    }
    if (!(x >= spec.min && x <= spec.max) || (integer && x != std::floor(x)))
        throwInputError(
            file, field,
            std::string("must be ") + (integer ? "an integer in " : "in ") + range +
                (allowUnsetZero && spec.unsetZero ? " or 0 (" + spec.defaultText + ")" : ""));
}

void checkTraceOptions(const TraceOptionValues& values, const TraceOptionNaming& naming) {
    for (const auto& [key, value] : values) {
        const TraceOptionSpec& spec = traceOption(key);
        checkTraceOption(spec, value, naming.file, naming.field(spec), naming.allowUnsetZero);
    }
}

std::string traceOptionDefaultText(const TraceOptionSpec& s) {
    return s.defaultText.empty() ? valueText(s, s.defaultValue) : s.defaultText;
}

std::string traceOptionHelp(const TraceOptionSpec& s) {
    return s.help + " (default: " + traceOptionDefaultText(s) + ")";
}

std::string traceOptionsMarkdown() {
    std::ostringstream out;
    out << "| option | API, Python, sweep key | default | range | meaning | offered by |\n"
        << "|---|---|---|---|---|---|\n";
    for (const TraceOptionSpec& s : traceOptionTable()) {
        std::string range;
        if (s.type == TraceOptionType::Name) {
            for (const std::string& n : s.names) range += (range.empty() ? "" : ", ") + n;
        } else {
            range = docNumber(s.min) + " .. " + docNumber(s.max);
            if (s.powerOfTwo) range = "a power of two, " + range;
        }
        std::string doc = s.doc;
        if (!s.excludes.empty()) {
            doc += "; not with";
            for (const std::string& k : s.excludes) doc += " `" + traceOption(k).cli + "`";
        }
        out << "| `" << s.cli << "` | `" << s.key << "` | " << traceOptionDefaultText(s) << " | "
            << range << " | " << doc << " |";
        const char* separator = " ";
        for (const auto& [bit, n] : kSurfaceNames)
            if (s.surfaces & bit) {
                out << separator << (bit == kSurfaceApi ? "API, Python" : n);
                separator = ", ";
            }
        out << " |\n";
    }
    return out.str();
}

std::string traceOptionsJson() {
    nlohmann::ordered_json options = nlohmann::ordered_json::array();
    for (const TraceOptionSpec& s : traceOptionTable()) {
        nlohmann::ordered_json j;
        j["cli"] = s.cli;
        j["key"] = s.key;
        j["type"] = traceOptionTypeName(s.type);
        if (s.type == TraceOptionType::Integer)
            j["default"] = int64_t(s.defaultValue.number);
        else if (s.type == TraceOptionType::Real)
            j["default"] = s.defaultValue.number;
        else
            j["default"] = s.defaultValue.text;
        if (s.type == TraceOptionType::Name) {
            j["names"] = s.names;
        } else {
            j["min"] = s.min;
            j["max"] = s.max;
            j["power_of_two"] = s.powerOfTwo;
            j["zero_means_default"] = s.unsetZero;
        }
        j["default_text"] = s.defaultText;
        j["help"] = s.help;
        j["excludes"] = s.excludes;
        j["surfaces"] = nlohmann::ordered_json::array();
        for (const auto& [bit, n] : kSurfaceNames)
            if (s.surfaces & bit) j["surfaces"].push_back(n);
        options.push_back(std::move(j));
    }
    return nlohmann::ordered_json{{"format_version", 1}, {"options", options}}.dump(2) + "\n";
}

}  // namespace so
