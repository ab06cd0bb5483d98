// gate --baseline end to end (label gl): the same technique against oracles traced with two seeds
// passes, a worse setting under the same label fails naming the metric; the JUnit XML and the
// Markdown summary are read back.
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli_run.h"
#include "gl_test_context.h"

namespace so {
namespace {

namespace fs = std::filesystem;
using namespace so::test;
using so::test::readBytes;

size_t count(const std::string& text, const std::string& what) {
    size_t n = 0;
    for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
    return n;
}

// The value of attribute `name` of the first element `tag` in `xml`.
std::string attribute(const std::string& xml, const std::string& tag, const std::string& name) {
    const size_t at = xml.find("<" + tag + " ");
    if (at == std::string::npos) return "";
    const size_t a = xml.find(name + "=\"", at);
    if (a == std::string::npos) return "";
    const size_t begin = a + name.size() + 2;
    return xml.substr(begin, xml.find('"', begin) - begin);
}

TEST(GateBaseline, TwoOracleSeedsPassAWorseSettingFailsNamingTheMetric) {
    REQUIRE_GL();
    const fs::path dir =
        fs::temp_directory_path() / ("so_gate_baseline_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    const std::string scene = std::string(SO_SCENES_DIR) + "/penumbra_square.scene.json";
    // The sampled oracle, whose noise between seeds the gate must allow for (auto would trace
    // this rect light exactly, the same at any seed).
    const auto compare = [&](const std::string& name, int seed, const std::string& techniques) {
        const so::test::RunResult r = so::test::run(
            "compare " + scene +
            " --penumbra sampled --width 80 --height 60 --frames 1 --no-cache --seed " +
            std::to_string(seed) + " --out " + (dir / name).string() + " " + techniques);
        ASSERT_EQ(r.exitCode, 0) << r.stdoutText << r.stderrText;
    };
    compare("seed1", 1, "--technique pcss --technique basic");
    compare("seed2", 2, "--technique pcss --technique basic");
    const std::string m1 = (dir / "seed1/metrics.json").string(),
                      m2 = (dir / "seed2/metrics.json").string();
    // The oracles differ (another seed), the techniques do not: no regression.
    so::test::RunResult r =
        so::test::run("gate " + m2 + " --baseline " + m1 + " --junit " +
                      (dir / "pass.xml").string() + " --summary " + (dir / "pass.md").string());
    EXPECT_EQ(r.exitCode, 0) << r.stdoutText << r.stderrText;
    EXPECT_EQ(r.stdoutText.find("REGRESSED"), std::string::npos) << r.stdoutText;
    EXPECT_NE(r.stdoutText.find(" 0 regressed"), std::string::npos) << r.stdoutText;
    const std::string passXml = readBytes(dir / "pass.xml");
    EXPECT_EQ(attribute(passXml, "testsuite", "name"), "shadow-oracle gate baseline");
    EXPECT_EQ(attribute(passXml, "testsuite", "failures"), "0");
    EXPECT_EQ(std::to_string(count(passXml, "<testcase ")),
              attribute(passXml, "testsuite", "tests"));
    EXPECT_GE(count(passXml, "<testcase "), 2u * 20u);  // two rows, 20+ quality metrics each
    EXPECT_EQ(count(passXml, "<failure"), 0u);
    EXPECT_NE(passXml.find("name=\"pcss penumbra_mae (baseline)\""), std::string::npos);
    const std::string passMd = readBytes(dir / "pass.md");
    EXPECT_NE(passMd.find("gate: passed"), std::string::npos) << passMd;
    EXPECT_NE(passMd.find("**0 worse**"), std::string::npos) << passMd;

    // A worse setting (pcss with one filter tap) under the same label, on a third seed; basic is
    // left out: its row is missing in the new run.
    compare("worse", 3, "--technique pcss:filter_samples=1");
    {
        const fs::path p = dir / "worse/metrics.json";
        nlohmann::json m = nlohmann::json::parse(readBytes(p));
        m["results"][0]["label"] = "pcss";
        std::ofstream(p) << m.dump(1);
    }
    // The limits file loosens nothing that matters here but must be read (format 2).
    std::ofstream(dir / "limits.json") << R"({"limits_format": 2,
        "default": {"acne_rate": 1.0},
        "baseline": {"metrics": {"penumbra_width_error_px.mean": {"abs": 0.5}}}})";
    r = so::test::run("gate " + (dir / "worse/metrics.json").string() + " --baseline " + m1 +
                      " --limits " + (dir / "limits.json").string() + " --junit " +
                      (dir / "fail.xml").string() + " --summary " + (dir / "fail.md").string());
    EXPECT_EQ(r.exitCode, 1) << r.stdoutText << r.stderrText;
    const std::string& out = r.stdoutText;
    EXPECT_NE(out.find("REGRESSED penumbra_square.scene.json panel pcss penumbra_mae: "),
              std::string::npos)
        << out;
    EXPECT_NE(out.find("beyond tolerance abs 0.001 + rel 5% + oracle noise "), std::string::npos)
        << out;
    EXPECT_NE(out.find("MISSING in new: penumbra_square.scene.json panel basic"), std::string::npos)
        << out;
    std::istringstream lines(out);
    size_t regressedLines = 0;
    for (std::string line; std::getline(lines, line);)
        if (line.rfind("REGRESSED ", 0) == 0) {
            ++regressedLines;
            EXPECT_NE(line.find(" pcss "), std::string::npos) << line;
            EXPECT_NE(line.find(" -> "), std::string::npos) << line;
        }
    EXPECT_GE(regressedLines, 3u) << out;
    // JUnit: the limits' suite and the baseline's; a failure per regression and one for the
    // missing row.
    const std::string failXml = readBytes(dir / "fail.xml");
    EXPECT_EQ(count(failXml, "<testsuite "), 2u) << failXml;
    EXPECT_EQ(count(failXml, "<failure"), regressedLines + 1) << failXml;
    EXPECT_NE(failXml.find("name=\"basic (row)\""), std::string::npos) << failXml;
    EXPECT_NE(failXml.find("REGRESSED penumbra_square.scene.json panel pcss penumbra_mae"),
              std::string::npos);
    // Markdown: the verdict, then one table row per worse metric and the missing row.
    const std::string md = readBytes(dir / "fail.md");
    EXPECT_NE(md.find("gate: FAILED"), std::string::npos) << md;
    EXPECT_NE(md.find("**" + std::to_string(regressedLines) + " worse**"), std::string::npos) << md;
    EXPECT_NE(md.find("| scene | light | label | metric | baseline | new | change |"),
              std::string::npos)
        << md;
    EXPECT_NE(md.find("| worse | penumbra_square.scene.json | panel | pcss | `penumbra_mae` |"),
              std::string::npos)
        << md;
    EXPECT_EQ(count(md, "| worse |"), regressedLines) << md;
    EXPECT_NE(md.find("| missing in new | penumbra_square.scene.json | panel | basic |"),
              std::string::npos)
        << md;
    // The baseline against itself passes; neither flag is bad input; schema 3 against 4 is too.
    EXPECT_EQ(so::test::run("gate " + m1 + " --baseline " + m1).exitCode, 0);
    r = so::test::run("gate " + m1);
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_NE(r.stderrText.find("--limits"), std::string::npos) << r.stderrText;
    {
        nlohmann::json m = nlohmann::json::parse(readBytes(m1));
        m["schema_version"] = 3;
        std::ofstream(dir / "v3.json") << m.dump();
    }
    r = so::test::run("gate " + m1 + " --baseline " + (dir / "v3.json").string());
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_NE(r.stderrText.find("v3.json: schema_version: "), std::string::npos) << r.stderrText;
    fs::remove_all(dir);
}

}  // namespace
}  // namespace so
