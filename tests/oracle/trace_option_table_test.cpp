// The trace option table (core/trace_option_table.h) against every surface that offers the
// options: the oracle's defaults, the API's struct, the command line's --help and checks,
// docs/cli.md and the Python stub. (The sweep spec's keys: sweep_spec_test.cpp; the Python
// module's keywords: tests/python.)
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "api/trace_option_fields.h"
#include "cli_run.h"
#include "core/error.h"
#include "core/trace_option_table.h"
#include "oracle/disk_bounds.h"
#include "oracle/exact_penumbra.h"
#include "oracle/trace_options.h"

namespace so {
namespace {

namespace fs = std::filesystem;
using test::readBytes;
using test::run;

std::set<std::string> keysOffered(unsigned surface) {
    std::set<std::string> keys;
    for (const TraceOptionSpec& s : traceOptionTable())
        if (s.surfaces & surface) keys.insert(s.key);
    return keys;
}

TEST(TraceOptionTable, RowsAreWellFormedAndTheirDefaultsValid) {
    std::set<std::string> keys, clis;
    for (const TraceOptionSpec& s : traceOptionTable()) {
        EXPECT_TRUE(keys.insert(s.key).second) << s.key;
        EXPECT_TRUE(clis.insert(s.cli).second) << s.cli;
        EXPECT_EQ(s.cli, "--" + std::regex_replace(s.key, std::regex("_"), "-")) << s.key;
        EXPECT_NE(s.surfaces, 0u) << s.key;
        EXPECT_FALSE(s.help.empty() || s.doc.empty()) << s.key;
        EXPECT_NO_THROW(checkTraceOption(s, s.defaultValue, "table", s.key, true)) << s.key;
        if (s.type == TraceOptionType::Name) {
            EXPECT_GE(s.names.size(), 2u) << s.key;
        } else {
            EXPECT_LT(s.min, s.max) << s.key;
        }
        for (const std::string& k : s.excludes) EXPECT_NO_THROW(traceOption(k)) << s.key;
    }
    EXPECT_THROW(traceOption("nope"), std::invalid_argument);
}

// Out of range, not an integer, not a power of two, not a name: one line naming the field, with
// the texts the command line printed before the table.
TEST(TraceOptionTable, ChecksNameTheFieldAndWhatIsValid) {
    const auto error = [](const std::string& key, TraceOptionValue v, bool unsetZero = false) {
        try {
            checkTraceOption(traceOption(key), v, "trace options", key, unsetZero);
        } catch (const InputError& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    EXPECT_EQ(error("max_spp", {8, ""}),
              "trace options: max_spp: must be an integer in [16, 1048576], got 8");
    EXPECT_EQ(error("max_spp", {100.5, ""}),
              "trace options: max_spp: must be an integer in [16, 1048576], got 100.5");
    EXPECT_EQ(error("target_error", {0.6, ""}),
              "trace options: target_error: must be in [0.0001, 0.5], got 0.6");
    EXPECT_EQ(error("target_error", {NAN, ""}),
              "trace options: target_error: must be in [0.0001, 0.5], got nan");
    EXPECT_EQ(error("bound_max_sides", {100, ""}),
              "trace options: bound_max_sides: 100 is not a power of two in [32, 16384]");
    EXPECT_EQ(error("bound_max_sides", {16, ""}),
              "trace options: bound_max_sides: 16 is not a power of two in [32, 16384]");
    EXPECT_EQ(error("bound_max_sides", {64, ""}), "");
    EXPECT_EQ(
        error("penumbra", {0, "exakt"}),
        "trace options: penumbra: unknown value \"exakt\" (valid: sampled, exact, both, auto)");
    EXPECT_EQ(error("exact_pixels", {0, "some"}),
              "trace options: exact_pixels: unknown value \"some\" (valid: penumbra, all)");
    EXPECT_EQ(error("width", {0, ""}),
              "trace options: width: must be an integer in [1, 16384], got 0");
    EXPECT_EQ(error("width", {0, ""}, true), "") << "the API's 0: the scene camera's";
    EXPECT_EQ(
        error("width", {-1, ""}, true),
        "trace options: width: must be an integer in [1, 16384] or 0 (the scene camera's), got -1");
    // The table's names are the oracle's: each parses, and the oracle's names are the table's.
    for (size_t k = 0; k < traceOption("penumbra").names.size(); ++k)
        EXPECT_EQ(penumbraMethodName(
                      parsePenumbraMethod(traceOption("penumbra").names[k], "t", "penumbra")),
                  traceOption("penumbra").names[k]);
    EXPECT_EQ(parseExactPixels(traceOption("exact_pixels").names[1], "t", "exact_pixels"), true);
}

// The fields of OracleOptions the table's rows write, as text.
std::string fingerprint(const OracleOptions& o) {
    std::ostringstream out;
    out.precision(17);
    out << o.width << " " << o.height << " " << o.threads << " " << o.area.seed << " "
        << o.area.targetError << " " << o.area.agreementTarget << " " << o.area.maxSpp << " "
        << o.area.fixedSpp << " " << o.verify.pixels << " " << o.verify.areaSamples << " "
        << penumbraMethodName(o.penumbra.method) << " " << o.penumbra.allPixels << " "
        << o.penumbra.bound.targetHalfWidth << " " << o.penumbra.bound.maxSides;
    return out.str();
}

// The oracle's own defaults (OracleOptions{}) are the table's, and every row has a place in them.
TEST(TraceOptionTable, OracleDefaultsAreTheTables) {
    std::vector<std::string> tableKeys;
    for (const TraceOptionSpec& s : traceOptionTable()) tableKeys.push_back(s.key);
    std::sort(tableKeys.begin(), tableKeys.end());
    EXPECT_EQ(appliedTraceOptionKeys(), tableKeys);
    EXPECT_EQ(fingerprint(OracleOptions{}), fingerprint(tableDefaultOracleOptions()));
    EXPECT_EQ(traceOption("bound_max_sides").min, double(DiskBoundOptions{}.minSides));
    EXPECT_EQ(traceOption("bound_max_sides").max, double(kMaxDiskSides));
    // Each row's setter writes its own field: a value other than the default changes the options.
    for (const TraceOptionSpec& s : traceOptionTable()) {
        TraceOptionValue v = s.defaultValue;
        if (s.type == TraceOptionType::Name)
            v.text = s.names.back() == v.text ? s.names.front() : s.names.back();
        else
            v.number = s.max;
        OracleOptions o;
        applyTraceOptions({{s.key, v}}, {"t", false, "", false}, o);
        EXPECT_NE(fingerprint(o), fingerprint(OracleOptions{})) << s.key;
    }
}

// shadow_oracle::TraceOptions{} holds the table's defaults under the table's API keys.
TEST(TraceOptionTable, ApiStructHoldsTheTablesDefaults) {
    const TraceOptionValues api = shadow_oracle::detail::traceOptionValues({});
    std::set<std::string> apiKeys;
    for (const auto& [key, value] : api) {
        apiKeys.insert(key);
        const TraceOptionSpec& s = traceOption(key);
        EXPECT_EQ(value.number, s.defaultValue.number) << key;
        EXPECT_EQ(value.text, s.defaultValue.text) << key;
    }
    EXPECT_EQ(apiKeys, keysOffered(kSurfaceApi));
}

// `trace --help` and `compare --help` list exactly the table's options for them, each with its
// default.
TEST(TraceOptionTable, CommandLineOffersTheTablesOptions) {
    for (const auto& [command, surface] :
         {std::pair{"trace", kSurfaceTrace}, std::pair{"compare", kSurfaceCompare}}) {
        const test::RunResult r = run(std::string(command) + " --help");
        ASSERT_EQ(r.exitCode, 0) << r.stderrText;
        for (const TraceOptionSpec& s : traceOptionTable()) {
            const bool listed = r.stdoutText.find("\n  " + s.cli + " ") != std::string::npos;
            EXPECT_EQ(listed, (s.surfaces & surface) != 0) << command << " " << s.cli;
            if (listed) {
                EXPECT_NE(r.stdoutText.find("(default: " + traceOptionDefaultText(s) + ")"),
                          std::string::npos)
                    << command << " " << s.cli;
            }
        }
    }
}

// A bad value is exit 2 with an error naming the option, before the scene is read.
TEST(TraceOptionTable, CommandLineRefusesWhatTheTableRefuses) {
    const std::string out = (fs::temp_directory_path() / "so_trace_option_table").string();
    for (const TraceOptionSpec& s : traceOptionTable()) {
        if (!(s.surfaces & kSurfaceTrace)) continue;
        const std::string bad = s.type == TraceOptionType::Name ? "nope"
                                : s.powerOfTwo                  ? "100"
                                                                : "-1";
        const test::RunResult r =
            run("trace no_such.scene.json --out " + out + " " + s.cli + " " + bad);
        EXPECT_EQ(r.exitCode, 2) << s.cli << ": " << r.stderrText;
        // The first line names the option (CLI11 adds "Run with --help" to its range errors).
        EXPECT_NE(r.stderrText.substr(0, r.stderrText.find('\n')).find(s.cli), std::string::npos)
            << s.cli << ": " << r.stderrText;
    }
    EXPECT_FALSE(fs::exists(out));
}

// docs/cli.md's trace option table is `trace-options --markdown`, and --json lists every row.
TEST(Docs, TraceOptionTableMatchesTheCode) {
    const std::string doc = readBytes(fs::path(SO_DOCS_DIR) / "cli.md");
    const std::string begin = "<!-- BEGIN trace-options (generated: scripts/update-docs) -->\n\n",
                      end = "<!-- END trace-options -->";
    const size_t a = doc.find(begin), b = doc.find(end);
    ASSERT_NE(a, std::string::npos);
    ASSERT_NE(b, std::string::npos);
    EXPECT_EQ(doc.substr(a + begin.size(), b - a - begin.size()),
              run("trace-options --markdown").stdoutText)
        << "docs/cli.md is stale: run scripts/update-docs";
    const nlohmann::json j = nlohmann::json::parse(run("trace-options --json").stdoutText);
    EXPECT_EQ(j["format_version"], 1);
    ASSERT_EQ(j["options"].size(), traceOptionTable().size());
    for (size_t i = 0; i < traceOptionTable().size(); ++i)
        EXPECT_EQ(j["options"][i]["key"], traceOptionTable()[i].key);
}

// python/shadow_oracle/__init__.pyi's trace() lists the table's API keys with their Python types
// and defaults, beside scene, points and progress.
TEST(TraceOptionTable, PythonStubListsTheTablesKeywords) {
    const std::string pyi = readBytes(SO_PYI_PATH);
    const size_t a = pyi.find("\ndef trace(\n"), b = pyi.find(") -> Trace: ...", a);
    ASSERT_NE(a, std::string::npos);
    ASSERT_NE(b, std::string::npos);
    const std::string block = pyi.substr(a, b - a);
    const std::regex param(R"(\n    (\w+): ([^=\n]+?)(?: = ([^,\n]+))?,)");
    std::map<std::string, std::pair<std::string, std::string>> stub;
    for (auto it = std::sregex_iterator(block.begin(), block.end(), param);
         it != std::sregex_iterator(); ++it)
        stub[(*it)[1]] = {(*it)[2], (*it)[3]};
    std::set<std::string> keys;
    for (const auto& [name, typeAndDefault] : stub)
        if (name != "scene" && name != "points" && name != "progress") keys.insert(name);
    EXPECT_EQ(keys, keysOffered(kSurfaceApi));
    for (const std::string& key : keysOffered(kSurfaceApi)) {
        const TraceOptionSpec& s = traceOption(key);
        const auto& [type, def] = stub[key];
        if (def.empty()) {
            ADD_FAILURE() << key << ": no default in the stub";
            continue;
        }
        if (s.type == TraceOptionType::Name) {
            EXPECT_EQ(type, "str") << key;
            EXPECT_EQ(def, "\"" + s.defaultValue.text + "\"") << key;
        } else {
            EXPECT_EQ(type, s.type == TraceOptionType::Integer ? "int" : "float") << key;
            EXPECT_EQ(std::stod(def), s.defaultValue.number) << key;
        }
    }
}

}  // namespace
}  // namespace so
