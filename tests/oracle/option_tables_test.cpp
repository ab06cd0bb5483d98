// The raster and comparison option tables (core/raster_option_table.h,
// core/compare_option_table.h) against the surfaces that offer them: the API's structs, the
// command line's --help and checks, `raster-options` and `compare-options`, docs/cli.md and the
// Python stub; and the trace table's rows against the oracle cache's key (oracle/oracle_cache.h).
// (The sweep spec's keys: sweep_spec_test.cpp; the Python module's keywords: tests/python.)
#include <filesystem>
#include <regex>
#include <set>
#include <string>
#include <utility>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli_run.h"
#include "core/compare_option_table.h"
#include "core/error.h"
#include "core/raster_option_table.h"
#include "core/trace_option_table.h"
#include "oracle/oracle_cache.h"
#include "oracle/trace_options.h"
#include "shadow_oracle/shadow_oracle.h"

namespace so {
namespace {

namespace fs = std::filesystem;
using test::readBytes;
using test::run;

// Each kind: its table, its listing command, its section of docs/cli.md.
struct Kind {
    const OptionTable* table;
    const char* command;
};
const Kind kKinds[] = {{&traceOptions(), "trace-options"},
                       {&rasterOptionTable(), "raster-options"},
                       {&compareOptionTable(), "compare-options"}};

TEST(OptionTables, RowsAreWellFormedAndTheirDefaultsValid) {
    std::set<std::string> keys;  // one key names one option across the kinds
    for (const Kind& kind : kKinds) {
        for (const OptionSpec& s : kind.table->rows) {
            EXPECT_TRUE(keys.insert(s.key).second) << s.key;
            EXPECT_EQ(s.cli, "--" + std::regex_replace(s.key, std::regex("_"), "-")) << s.key;
            EXPECT_NE(s.surfaces, 0u) << s.key;
            EXPECT_FALSE(s.help.empty() || s.doc.empty()) << s.key;
            EXPECT_NO_THROW(checkOption(s, s.defaultValue, "table", s.key, true)) << s.key;
            if (s.type != OptionType::Name) {
                EXPECT_LT(s.min, s.max) << s.key;
            }
            for (const std::string& k : s.excludes) EXPECT_NO_THROW(kind.table->at(k)) << s.key;
        }
        EXPECT_THROW(kind.table->at("nope"), std::invalid_argument) << kind.command;
    }
}

// The structs' defaults are the rows' (RasterOptions, ComparisonOptions, ... take the constants
// the rows use), and the public API's structs spell the same defaults.
TEST(OptionTables, DefaultsAreTheRowsOnEverySurface) {
    EXPECT_EQ(rasterOption("frames").defaultValue.number, kDefaultFrames);
    EXPECT_EQ(rasterOption("warmup").defaultValue.number, kDefaultWarmup);
    EXPECT_EQ(compareOption("boundary_radius").defaultValue.number, kDefaultBoundaryRadius);
    const shadow_oracle::RenderOptions render;
    EXPECT_EQ(render.frames, rasterOption("frames").defaultValue.number);
    EXPECT_EQ(render.warmup, rasterOption("warmup").defaultValue.number);
    const shadow_oracle::CompareOptions compare;
    EXPECT_EQ(compare.frames, rasterOption("frames").defaultValue.number);
    EXPECT_EQ(compare.warmup, rasterOption("warmup").defaultValue.number);
    EXPECT_EQ(compare.boundaryRadius, compareOption("boundary_radius").defaultValue.number);
    EXPECT_EQ(shadow_oracle::TraceOptions{}.maxSpp, traceOption("max_spp").defaultValue.number);
}

TEST(OptionTables, ChecksNameTheFieldAndTheRange) {
    const auto error = [](const OptionSpec& s, double v) {
        try {
            checkOption(s, {v, ""}, "render options", s.key, false);
        } catch (const InputError& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    EXPECT_EQ(error(rasterOption("frames"), 0),
              "render options: frames: must be an integer in [1, 1000], got 0");
    EXPECT_EQ(error(rasterOption("warmup"), 1.5),
              "render options: warmup: must be an integer in [0, 1000], got 1.5");
    EXPECT_EQ(error(compareOption("boundary_radius"), 65),
              "render options: boundary_radius: must be an integer in [0, 64], got 65");
    EXPECT_EQ(error(rasterOption("frames"), kDefaultFrames), "");
}

// `raster --help` and `compare --help` list exactly the tables' options for them, each with its
// default; a value out of range is exit 2 naming the flag, before the scene is read.
TEST(OptionTables, CommandLineOffersAndChecksTheTablesOptions) {
    const std::pair<const char*, OptionSurface> commands[] = {{"raster", kSurfaceRaster},
                                                              {"compare", kSurfaceCompare}};
    for (const auto& [command, surface] : commands) {
        const test::RunResult r = run(std::string(command) + " --help");
        ASSERT_EQ(r.exitCode, 0) << r.stderrText;
        for (const OptionTable* table : {&rasterOptionTable(), &compareOptionTable()})
            for (const OptionSpec& s : table->rows) {
                const bool listed = r.stdoutText.find("\n  " + s.cli + " ") != std::string::npos;
                EXPECT_EQ(listed, (s.surfaces & surface) != 0) << command << " " << s.cli;
                if (listed) {
                    EXPECT_NE(r.stdoutText.find("(default: " + optionDefaultText(s) + ")"),
                              std::string::npos)
                        << command << " " << s.cli;
                }
            }
    }
    const std::string out = (fs::temp_directory_path() / "so_option_tables").string();
    for (const OptionTable* table : {&rasterOptionTable(), &compareOptionTable()})
        for (const OptionSpec& s : table->rows) {
            // A flag takes no value to be out of range.
            if (!(s.surfaces & kSurfaceCompare) || s.type == OptionType::Flag) continue;
            const test::RunResult r =
                run("compare no_such.scene.json --technique shadow --out " + out + " " + s.cli +
                    " " + std::to_string(int64_t(s.max) + 1));
            EXPECT_EQ(r.exitCode, 2) << s.cli << ": " << r.stderrText;
            EXPECT_NE(r.stderrText.substr(0, r.stderrText.find('\n')).find(s.cli),
                      std::string::npos)
                << s.cli << ": " << r.stderrText;
        }
    EXPECT_FALSE(fs::exists(out));
}

// `raster-options --json` and `compare-options --json` list every row with its default, and
// docs/cli.md's tables are the --markdown output (scripts/update-docs).
TEST(Docs, RasterAndCompareOptionTablesMatchTheCode) {
    const std::string doc = readBytes(fs::path(SO_DOCS_DIR) / "cli.md");
    for (const Kind& kind : kKinds) {
        const std::string name = kind.command;
        const nlohmann::json j = nlohmann::json::parse(run(name + " --json").stdoutText);
        EXPECT_EQ(j["format_version"], 1);
        ASSERT_EQ(j["options"].size(), kind.table->rows.size()) << name;
        for (size_t i = 0; i < kind.table->rows.size(); ++i) {
            const OptionSpec& s = kind.table->rows[i];
            EXPECT_EQ(j["options"][i]["key"], s.key);
            if (s.type == OptionType::Flag) {
                EXPECT_EQ(j["options"][i]["default"].get<bool>(), s.defaultValue.number != 0.0);
            } else if (s.type != OptionType::Name) {
                EXPECT_EQ(j["options"][i]["default"].get<double>(), s.defaultValue.number);
            }
        }
        const std::string begin =
                              "<!-- BEGIN " + name + " (generated: scripts/update-docs) -->\n\n",
                          end = "<!-- END " + name + " -->";
        const size_t a = doc.find(begin), b = doc.find(end);
        ASSERT_NE(a, std::string::npos) << name;
        ASSERT_NE(b, std::string::npos) << name;
        EXPECT_EQ(doc.substr(a + begin.size(), b - a - begin.size()),
                  run(name + " --markdown").stdoutText)
            << "docs/cli.md is stale: run scripts/update-docs";
    }
}

// python/shadow_oracle/__init__.pyi's render() and compare() spell the rows' defaults.
TEST(OptionTables, PythonStubSpellsTheRowsDefaults) {
    const std::string pyi = readBytes(SO_PYI_PATH);
    for (const char* function : {"render", "compare"}) {
        const size_t a = pyi.find("\ndef " + std::string(function) + "(\n");
        ASSERT_NE(a, std::string::npos) << function;
        const std::string block = pyi.substr(a, pyi.find(") ->", a) - a);
        for (const OptionTable* table : {&rasterOptionTable(), &compareOptionTable()})
            for (const OptionSpec& s : table->rows) {
                if (!(s.surfaces & kSurfaceApi)) continue;
                if (std::string(function) == "render" && table != &rasterOptionTable()) continue;
                const std::regex param("\n    " + s.key + R"(: int = (\d+),)");
                std::smatch m;
                ASSERT_TRUE(std::regex_search(block, m, param)) << function << " " << s.key;
                EXPECT_EQ(std::stod(m[1]), s.defaultValue.number) << function << " " << s.key;
            }
    }
}

// Every trace option that changes the result is in the oracle cache's key: two values of it give
// two keys (else a second run with another value would read the first run's oracle); the rows
// that do not (threads) leave the key as it is.
TEST(OptionTables, CacheKeyHoldsEveryResultChangingTraceOption) {
    Scene scene;
    scene.camera.width = 64;
    scene.camera.height = 48;
    scene.contentHash = "a scene";
    const std::string base = oracleCacheKey(scene, OracleOptions{});
    size_t changing = 0;
    for (const TraceOptionSpec& s : traceOptionTable()) {
        TraceOptionValue v = s.defaultValue;
        if (s.type == OptionType::Name)
            v.text = s.names.back() == v.text ? s.names.front() : s.names.back();
        else
            v.number = s.powerOfTwo ? s.min : s.max;
        OracleOptions o;
        applyTraceOptions({{s.key, v}}, {"t", false, "", false}, o);
        EXPECT_EQ(oracleCacheKey(scene, o) != base, s.changesResult) << s.key;
        changing += s.changesResult;
        if (s.changesResult) {
            EXPECT_TRUE(resultOptionsJson(o, scene.camera).contains(s.key)) << s.key;
        }
    }
    EXPECT_GT(changing, 0u);
    EXPECT_FALSE(traceOption("threads").changesResult) << "the output is bit-identical for any N";
}

}  // namespace
}  // namespace so
